// Copyright (c) 2026, the tmr authors. BSD-3-Clause.
#pragma once

#include <string>

#include "tmr/colmap/tmr_mapper.h"

namespace tmr {

// report.json of a run.
std::string ReportJson(const TmrMapperReport& report);

// Fills the report's tasks_end_s, critical_path_s and projected_wall_s from
// its rows (start_s, seconds, depends; reused rows count 0 s) and
// total_seconds, for a run on `num_workers` workers. What comes before the
// first task-graph row (partition, task databases) and the wall time that
// no row accounts for when the rows are replayed on `num_workers` (gaps
// between the assembly's steps, writing the models) are taken as serial
// and added to every projection.
void SummarizeTimeline(int num_workers, TmrMapperReport* report);

// One progress line: the wall time after the parallel tasks and its share,
// the critical path, and the projected wall time on 16 workers.
std::string DescribeTimeline(const TmrMapperReport& report);

}  // namespace tmr
