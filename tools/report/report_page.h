// Copyright (c) 2026, the tmr authors. BSD-3-Clause.
// report.html: one page per run that opens from disk, with no server and no
// network (its data, script and style inline), showing the partition, the
// timeline of tasks and merges, the links between models and the models in
// 3D (docs/mapper.md, "The report page").
#pragma once

#include <functional>
#include <string>

#include "drawing/partition_picture.h"
#include "tmr/io/database_reader.h"

namespace tmr {

struct ReportPageOptions {
  // Points drawn of all models together, shared out by model size; the page
  // says how many of how many it draws.
  int max_drawn_points = 200000;
  // Above this many images the partition map is left out (its layout
  // takes minutes, its dots are unreadable).
  int max_map_images = 20000;

  bool Check() const { return max_drawn_points >= 0 && max_map_images >= 0; }
};

// The page's data (JSON): report.json, the tree's kernels, the models
// output_path/0, 1, ... (cameras, and points subsampled), output_path/
// eval.json when tmr_eval wrote one there, and `map` (null: no partition
// map). Throws std::runtime_error for unreadable input.
std::string ReportPageData(const std::string& output_path,
                           const PartitionMap* map,
                           const ReportPageOptions& options);

// The page around `data` (ReportPageData).
std::string ReportPageHtml(const std::string& data);

// A run's pictures, as tmr_mapper and tmr_reconstruct write them at the
// end: partition.png and report.html in output_path, from one layout of the
// partition map (none above options.max_map_images: the page then has no
// map and partition.png is not drawn, which `progress` hears). Throws
// std::runtime_error for unreadable input.
void WriteRunPictures(const std::string& database_path,
                      const MatchGraphOptions& match_graph,
                      const std::string& output_path,
                      const std::function<void(const std::string&)>& progress,
                      const ReportPageOptions& options = {});

}  // namespace tmr
