// Copyright (c) 2026, the tmr authors. BSD-3-Clause.
// bench_adjustment DATABASE MODEL [MAX_BLOCK_IMAGES]
// Time and peak memory of tmr's refinement of a merged model (re-linked
// tracks, global bundle adjustment, filtering: RefineModel, as tmr_mapper
// refines a merged scene), the largest step of tmr_mapper's memory; whole
// (default) or by blocks of at most MAX_BLOCK_IMAGES
// (--Tmr.ba_max_block_images). The database is read-only.
#include <sys/resource.h>

#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <string>

#include "tmr/colmap/model_refinement.h"

namespace {

// Peak resident memory of this process so far, MiB.
long PeakMiB() {
  rusage usage;
  getrusage(RUSAGE_SELF, &usage);
  return usage.ru_maxrss / 1024;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 3 && argc != 4) {
    std::cerr << "usage: bench_adjustment DATABASE MODEL [MAX_BLOCK_IMAGES]\n";
    return 2;
  }
  tmr::ModelRefinementOptions options;
  if (argc == 4) {
    char* end = nullptr;
    const long long value = std::strtoll(argv[3], &end, 10);
    if (*argv[3] == '\0' || *end != '\0' || value < 0 || value > 1000000) {
      std::cerr << "bench_adjustment: error: MAX_BLOCK_IMAGES must be a "
                   "number from 0 to 1000000, not '"
                << argv[3] << "'\n";
      return 2;
    }
    options.max_block_images = static_cast<int>(value);
  }
  tmr::ModelRefinementReport report;
  std::string error;
  if (!tmr::RefineModel(argv[1], argv[2], "",
                        std::filesystem::temp_directory_path().string(),
                        options, &report, &error)) {
    std::cerr << "bench_adjustment: error: " << error << "\n";
    return 1;
  }
  std::cout << "loaded: " << report.num_images << " images in "
            << report.load_seconds << " s, peak RSS " << report.load_peak_mib
            << " MiB\n"
            << "refined in " << report.refine_seconds << " s, peak RSS "
            << PeakMiB() << " MiB, mean reprojection error "
            << report.mean_reprojection_error_px << " px\n"
            << report.message << "\n";
  return 0;
}
