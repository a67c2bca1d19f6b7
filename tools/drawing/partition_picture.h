// Copyright (c) 2026, the tmr authors. BSD-3-Clause.
// The partition picture of tmr_partition and tmr_mapper (OpenCV).
#pragma once

#include <string>

#include "tmr/partition/tmr_tree.h"
#include "tmr/scene/image_graph.h"

namespace tmr {

// Draws the image graph with a force-directed layout (ForceDirectedLayout,
// seeded): images coloured by leaf cluster (one hue per image
// cluster), kernel images outlined in black, exemplars as large squares,
// unclustered images as grey crosses. Writes a PNG; false on failure.
bool DrawPartitionPicture(const ImageGraph& similarity, const TmrTree& tree,
                          const std::string& png_path, int size_px = 1600);

}  // namespace tmr
