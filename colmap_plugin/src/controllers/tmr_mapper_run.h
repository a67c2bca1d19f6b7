// Copyright (c) 2026, the tmr authors. BSD-3-Clause.
#pragma once

#include <chrono>
#include <functional>
#include <string>

#include "controllers/tmr_mapper_stages.h"
#include "tmr/colmap/tmr_mapper.h"

namespace tmr {

// What the one-process run (tmr_mapper.cc) and the staged entry points
// (tmr_mapper_staged.cc) do alike.

// Checks the options and creates output_path; copies min_num_matches into
// the match-graph options.
bool PrepareTmrMapper(const TmrMapperOptions& options,
                      TmrMapperOptions* effective, std::string* error);

// options.num_threads, or the machine's cores.
int TmrMapperThreads(const TmrMapperOptions& options);

// report.json, and the work folder removed unless keep_work. With
// `timeline` (the one-process run, whose rows carry the task graph's
// timing), the timeline is summarised first.
void FinishTmrMapper(const TmrMapperOptions& o, const TmrMapperStages& stages,
                     std::chrono::steady_clock::time_point start, bool timeline,
                     const std::function<void(const std::string&)>& progress,
                     TmrMapperReport* report);

}  // namespace tmr
