// Copyright (c) 2026, the tmr authors. BSD-3-Clause.
#pragma once

#include <colmap/scene/reconstruction.h>

#include "tmr/colmap/model_evaluation.h"

namespace tmr {

// EvaluateModel on reconstructions in memory.
ModelEvaluation EvaluateReconstruction(const colmap::Reconstruction& reference,
                                       const colmap::Reconstruction& model,
                                       const ModelEvaluationOptions& options);

// Reads a COLMAP model folder (binary or text); throws std::runtime_error.
colmap::Reconstruction ReadModel(const std::string& path);

}  // namespace tmr
