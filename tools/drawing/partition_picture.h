// Copyright (c) 2026, the tmr authors. BSD-3-Clause.
// The partition picture of tmr_partition and tmr_mapper (OpenCV).
#pragma once

#include <string>

#include "tmr/io/database_reader.h"
#include "tmr/partition/tmr_tree.h"
#include "tmr/scene/image_graph.h"

namespace tmr {

// Draws the image graph with a force-directed layout (ForceDirectedLayout,
// seeded): images coloured by leaf cluster (one hue per image
// cluster), kernel images outlined in black, exemplars as large squares,
// unclustered images as grey crosses. Writes a PNG; false on failure.
bool DrawPartitionPicture(const ImageGraph& similarity, const TmrTree& tree,
                          const std::string& png_path, int size_px = 1600);

// Draws output_path/partition.png of a run from output_path/tree.json and
// the database's similarity graph; false (nothing drawn) above 20,000
// images, where the layout would take minutes. Throws on unreadable input.
bool DrawRunPartitionPicture(const std::string& database_path,
                             const MatchGraphOptions& match_graph,
                             const std::string& output_path);

}  // namespace tmr
