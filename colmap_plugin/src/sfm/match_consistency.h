// Copyright (c) 2026, the tmr authors. BSD-3-Clause.
#pragma once

#include <colmap/scene/database.h>
#include <colmap/scene/reconstruction.h>

#include "tmr/colmap/match_consistency_options.h"

namespace tmr {

// A check of a model that needs no ground truth. A model holds only the
// matches its tracks use; the verified matches between two registered
// images that no common track holds are triangulated with the model's
// poses and cameras. On a correct model they reproject within the
// verification threshold (the model's relative pose satisfies the epipolar
// constraint they were verified with); where the mapper settled a group of
// photos in a wrong place, or traded focal length against depth, many do
// not (figures: docs/mapper.md, step 3). Image ids of `model`
// must be those of `database`.
MatchConsistency CheckMatchConsistency(const colmap::Reconstruction& model,
                                       const colmap::Database& database,
                                       const MatchConsistencyOptions& options);

}  // namespace tmr
