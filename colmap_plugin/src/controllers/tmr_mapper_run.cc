// Copyright (c) 2026, the tmr authors. BSD-3-Clause.
#include "controllers/tmr_mapper_run.h"

#include <algorithm>
#include <filesystem>
#include <thread>

#include "controllers/tmr_mapper_report.h"
#include "tmr/io/atomic_file.h"
#include "tmr/util/process.h"

namespace tmr {

namespace fs = std::filesystem;

bool PrepareTmrMapper(const TmrMapperOptions& options,
                      TmrMapperOptions* effective, std::string* error) {
  if (!options.Check(error)) return false;
  if (!options.image_path.empty() && !fs::is_directory(options.image_path)) {
    *error = "image_path '" + options.image_path + "' is not a folder";
    return false;
  }
  std::error_code ec;
  fs::create_directories(options.output_path, ec);
  if (ec) {
    *error = "cannot create output_path '" + options.output_path +
             "': " + ec.message();
    return false;
  }
  *effective = options;
  effective->match_graph.min_num_matches = options.mapper.min_num_matches;
  return true;
}

int TmrMapperThreads(const TmrMapperOptions& options) {
  return options.num_threads > 0
             ? options.num_threads
             : static_cast<int>(
                   std::max(1u, std::thread::hardware_concurrency()));
}

void FinishTmrMapper(const TmrMapperOptions& o, const TmrMapperStages& stages,
                     std::chrono::steady_clock::time_point start, bool timeline,
                     const std::function<void(const std::string&)>& progress,
                     TmrMapperReport* report) {
  report->total_seconds = SecondsSince(start);
  if (timeline) {
    SummarizeTimeline(TmrMapperThreads(o), report);
    if (progress) progress(DescribeTimeline(*report));
  }
  WriteFileAtomically((fs::path(o.output_path) / "report.json").string(),
                      ReportJson(*report));
  if (!o.keep_work) fs::remove_all(stages.work().folder());
}

}  // namespace tmr
