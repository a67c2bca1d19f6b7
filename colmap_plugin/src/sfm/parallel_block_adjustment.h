// Copyright (c) 2026, the tmr authors. BSD-3-Clause.
//
// Bundle adjustment of a model's blocks side by side: the full adjustment
// of a merged scene whose large-scale shape an adjustment on its longest
// tracks has just fixed, spread over the workers (AdjustBlocksAtOnce).
#pragma once

#include <colmap/estimators/bundle_adjustment.h>
#include <colmap/scene/reconstruction.h>

#include <string>
#include <vector>

#include "sfm/block_adjustment.h"

namespace tmr {

// What AdjustBlocksAtOnce did.
struct BlocksAdjustment {
  // Each block's adjustment, its copy included, in the blocks' order.
  std::vector<double> block_seconds;
  // Wall time of the whole: blocks, then writing back and the seam points.
  double seconds = 0;
  BlockAdjustmentTotals totals;
  // One line: blocks, iterations, cost.
  std::string Describe() const;
};

// Adjusts `blocks` (disjoint sets of registered images of `model`, as
// CovisibleImageBlocks cuts them) each as AdjustBlock does, on a copy of
// its part of the model: its images, its points, and the images outside
// that observe them, held at the poses they had before. At most
// `num_workers` blocks run at once. Then each block's poses and cameras are
// written back; a point that images of several blocks observe takes the
// position its block with the most of those observations gave it (the
// first such block on a tie), then is triangulated again from the adjusted
// poses where that fits better (RetriangulateIfBetter); a camera that
// images of several blocks share is held. The result does not depend on
// num_workers: every block reads the model as it was.
BlocksAdjustment AdjustBlocksAtOnce(
    const std::vector<std::vector<colmap::image_t>>& blocks,
    const colmap::BundleAdjustmentOptions& options, int num_workers,
    colmap::Reconstruction* model);

}  // namespace tmr
