// Copyright (c) 2026, the tmr authors. BSD-3-Clause.
#include "tmr/colmap/model_refinement.h"

#include <colmap/util/logging.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <memory>
#include <vector>

#include "io/model_files.h"
#include "io/task_database.h"
#include "merge/merged_model_refinement.h"
#include "tmr/util/process.h"

namespace tmr {

bool ModelRefinementOptions::Check(std::string* error) const {
  auto fail = [&](const std::string& message) {
    if (error) *error = message;
    return false;
  };
  if (max_block_images < 0) return fail("max_block_images must be >= 0");
  if (num_threads < 1) return fail("num_threads must be >= 1");
  if (min_num_matches < 1) return fail("min_num_matches must be >= 1");
  return true;
}

bool RefineModel(const std::string& database_path,
                 const std::string& model_path, const std::string& output_path,
                 const std::string& scratch_folder,
                 const ModelRefinementOptions& options,
                 ModelRefinementReport* report, std::string* error) {
  THROW_CHECK_NOTNULL(report);
  THROW_CHECK_NOTNULL(error);
  if (!options.Check(error)) return false;
  auto model = std::make_shared<colmap::Reconstruction>();
  try {
    *model = ReadModel(model_path);
  } catch (const std::exception& e) {
    *error = e.what();
    return false;
  }
  const auto load_start = std::chrono::steady_clock::now();
  const std::vector<colmap::image_t> registered = model->RegImageIds();
  const std::vector<uint32_t> ids(registered.begin(), registered.end());
  const std::string scratch =
      (std::filesystem::path(scratch_folder) /
       ("refine_model_" + std::to_string(getpid()) + ".db"))
          .string();
  const auto cache = LoadTaskDatabaseCache(
      database_path, ids, scratch, options.min_num_matches,
      /*ignore_watermarks=*/false, error);
  std::error_code ec;
  std::filesystem::remove(scratch, ec);
  if (!cache) return false;
  *report = ModelRefinementReport();
  report->num_images = static_cast<int>(ids.size());
  report->load_seconds = SecondsSince(load_start);
  report->load_peak_mib = ReadProcessMemory().peak_mib;
  colmap::IncrementalPipelineOptions mapper;
  mapper.num_threads = options.num_threads;
  MergedModelAdjustment adjustment;
  adjustment.max_block_images = static_cast<size_t>(options.max_block_images);
  const auto refine_start = std::chrono::steady_clock::now();
  report->message = RefineMergedModel(cache, mapper, adjustment, model).report;
  report->refine_seconds = SecondsSince(refine_start);
  report->mean_reprojection_error_px = model->ComputeMeanReprojectionError();
  if (!output_path.empty() && !WriteModelAtomically(*model, output_path)) {
    *error = "cannot write model '" + output_path + "'";
    return false;
  }
  return true;
}

}  // namespace tmr
