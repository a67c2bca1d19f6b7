// Copyright (c) 2026, the tmr authors. BSD-3-Clause.
#pragma once

#include <colmap/scene/reconstruction.h>

#include "tmr/colmap/model_evaluation.h"

namespace tmr {

// EvaluateModel on reconstructions in memory.
ModelEvaluation EvaluateReconstruction(const colmap::Reconstruction& reference,
                                       const colmap::Reconstruction& model,
                                       const ModelEvaluationOptions& options);

}  // namespace tmr
