// Copyright (c) 2026, the tmr authors. BSD-3-Clause.
// bench_adjustment DATABASE MODEL [MAX_BLOCK_IMAGES]
// Time and peak memory of tmr's refinement of a merged model (re-linked
// tracks, global bundle adjustment, filtering: RefineMergedModel), the
// largest step of tmr_mapper's memory; whole (default) or by blocks of at
// most MAX_BLOCK_IMAGES (--Tmr.ba_max_block_images). The database is
// read-only.
#include <sys/resource.h>
#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <iostream>

#include "io/task_database.h"
#include "merge/merged_model_refinement.h"

int main(int argc, char** argv) {
  if (argc != 3 && argc != 4) {
    std::cerr << "usage: bench_adjustment DATABASE MODEL [MAX_BLOCK_IMAGES]\n";
    return 2;
  }
  size_t max_block_images = 0;
  if (argc == 4) {
    char* end = nullptr;
    const long long value = std::strtoll(argv[3], &end, 10);
    if (*argv[3] == '\0' || *end != '\0' || value < 0) {
      std::cerr << "bench_adjustment: error: MAX_BLOCK_IMAGES must be a "
                   "number >= 0, not '"
                << argv[3] << "'\n";
      return 2;
    }
    max_block_images = static_cast<size_t>(value);
  }
  auto model = std::make_shared<colmap::Reconstruction>();
  try {
    model->Read(argv[2]);
  } catch (const std::exception& e) {
    std::cerr << "bench_adjustment: error: cannot read '" << argv[2]
              << "': " << e.what() << "\n";
    return 1;
  }
  const std::vector<colmap::image_t> registered = model->RegImageIds();
  const std::vector<uint32_t> ids(registered.begin(), registered.end());
  const std::string scratch =
      (std::filesystem::temp_directory_path() /
       ("bench_adjustment_" + std::to_string(getpid()) + ".db"))
          .string();
  std::string error;
  auto cache =
      tmr::LoadTaskDatabaseCache(argv[1], ids, scratch, 15, false, &error);
  if (!cache) {
    std::cerr << "bench_adjustment: error: " << error << "\n";
    return 1;
  }
  std::filesystem::remove(scratch);
  rusage usage;
  getrusage(RUSAGE_SELF, &usage);
  std::cout << "loaded: " << ids.size() << " images, peak RSS "
            << usage.ru_maxrss / 1024 << " MiB\n";
  colmap::IncrementalPipelineOptions options;
  options.num_threads = 2;
  const auto start = std::chrono::steady_clock::now();
  tmr::MergedModelAdjustment adjustment;
  adjustment.max_block_images = max_block_images;
  const std::string report =
      tmr::RefineMergedModel(cache, options, adjustment, model).report;
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start)
          .count();
  getrusage(RUSAGE_SELF, &usage);
  std::cout << "refined in " << seconds << " s, peak RSS "
            << usage.ru_maxrss / 1024 << " MiB, mean reprojection error "
            << model->ComputeMeanReprojectionError() << " px\n"
            << report << "\n";
  return 0;
}
