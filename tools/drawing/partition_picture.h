// Copyright (c) 2026, the tmr authors. BSD-3-Clause.
// The partition picture of tmr_partition and tmr_mapper (OpenCV).
#pragma once

#include <array>
#include <optional>
#include <string>
#include <vector>

#include "tmr/io/database_reader.h"
#include "tmr/partition/tmr_tree.h"
#include "tmr/scene/image_graph.h"

namespace tmr {

// A run's partition laid out for drawing: the database's similarity graph,
// the run's tree (tree.json, vertices numbered as the graph's) and a
// position per image (ForceDirectedLayout, seeded).
struct PartitionMap {
  ImageGraph similarity;
  TmrTree tree;
  std::vector<std::array<double, 2>> layout;
};

// The partition map of the run in output_path (tree.json) on its database;
// nullopt above `max_images` images, where the layout would take minutes
// (the tree's size decides before the match graph is read). Throws on
// unreadable input.
std::optional<PartitionMap> ReadRunPartitionMap(
    const std::string& database_path, const MatchGraphOptions& match_graph,
    const std::string& output_path, size_t max_images = 20000);

// Draws a partition map: images coloured by leaf cluster (one hue per image
// cluster), kernel images outlined in black, exemplars as large squares,
// unclustered images as grey crosses. Writes a PNG; false on failure.
bool DrawPartitionPicture(const PartitionMap& map, const std::string& png_path,
                          int size_px = 1600);

// The same, laid out here.
bool DrawPartitionPicture(const ImageGraph& similarity, const TmrTree& tree,
                          const std::string& png_path, int size_px = 1600);

// Draws output_path/partition.png of a run (ReadRunPartitionMap); false
// (nothing drawn) above 20,000 images. Throws on unreadable input.
bool DrawRunPartitionPicture(const std::string& database_path,
                             const MatchGraphOptions& match_graph,
                             const std::string& output_path);

}  // namespace tmr
