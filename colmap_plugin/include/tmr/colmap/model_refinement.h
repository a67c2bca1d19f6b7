// Copyright (c) 2026, the tmr authors. BSD-3-Clause.
// A model refined as tmr_mapper refines a merged scene, from files: what
// tools/bench/bench_adjustment measures.
#pragma once

#include <string>

namespace tmr {

struct ModelRefinementOptions {
  // Adjust by blocks of at most this many images (--Tmr.ba_max_block_images);
  // 0: the whole model in one adjustment.
  int max_block_images = 0;
  // Threads of the adjustment.
  int num_threads = 2;
  // Pairs with fewer verified matches are left out, as COLMAP's mapper
  // leaves them (--Mapper.min_num_matches).
  int min_num_matches = 15;
  bool Check(std::string* error = nullptr) const;
};

struct ModelRefinementReport {
  int num_images = 0;             // registered images refined
  double load_seconds = 0.0;      // the database's correspondences
  double load_peak_mib = 0.0;     // the process's peak memory once loaded
  double refine_seconds = 0.0;    // re-linking, adjustment, filtering
  double mean_reprojection_error_px = 0.0;  // after
  std::string message;  // the adjustment's solver and Ceres' report
};

// Reads the model at `model_path`, loads the correspondences of its
// registered images from the database (read-only, through a task database
// in `scratch_folder`, removed after), then re-links its tracks, adjusts
// and filters it (RefineMergedModel) and, unless `output_path` is empty,
// writes it there. False with the reason in `error`. `report` and `error`
// must not be null.
bool RefineModel(const std::string& database_path,
                 const std::string& model_path, const std::string& output_path,
                 const std::string& scratch_folder,
                 const ModelRefinementOptions& options,
                 ModelRefinementReport* report, std::string* error);

}  // namespace tmr
