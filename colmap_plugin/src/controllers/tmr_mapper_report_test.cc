// Copyright (c) 2026, the tmr authors. BSD-3-Clause.
#include "controllers/tmr_mapper_report.h"

#include <gtest/gtest.h>

namespace tmr {
namespace {

TmrTaskReport Row(const std::string& name, double start, double seconds,
                  std::vector<int> depends, bool in_task_graph) {
  TmrTaskReport row;
  row.name = name;
  row.start_s = start;
  row.seconds = seconds;
  row.depends = std::move(depends);
  row.in_task_graph = in_task_graph;
  return row;
}

// A run on two workers: 2 s of partition, two kernels with a leaf each and
// their cluster merges on the task graph (ending at 16 s), then two
// assembly steps of 10 s and 5 s, and 1 s of writing.
TmrMapperReport TwoKernelRun() {
  TmrMapperReport r;
  r.tasks = {Row("kernel 0", 2, 8, {}, true),
             Row("kernel 1", 2, 4, {}, true),
             Row("leaf 1.0", 6, 4, {1}, true),
             Row("leaf 0.0", 10, 5, {0}, true),
             Row("merge cluster 1", 10, 1, {1, 2}, true),
             Row("merge cluster 0", 15, 1, {0, 3}, true),
             Row("merge a model", 16, 10, {0, 1, 2, 3, 4, 5}, false),
             Row("refine merged model", 26, 5, {6}, false)};
  r.total_seconds = 32;
  return r;
}

TEST(SummarizeTimeline, CriticalPathAndProjections) {
  TmrMapperReport r = TwoKernelRun();
  SummarizeTimeline(2, &r);
  EXPECT_DOUBLE_EQ(r.tasks_end_s, 16);
  // 2 s before the graph, kernel 0 + leaf 0.0 + merge 0 + both assembly
  // steps (29 s), and the 1 s no row accounts for.
  EXPECT_DOUBLE_EQ(r.critical_path_s, 2 + 8 + 5 + 1 + 10 + 5 + 1);
  ASSERT_EQ(r.projected_wall_s.size(), 5u);
  EXPECT_EQ(r.projected_wall_s[0].first, 2);
  EXPECT_DOUBLE_EQ(r.projected_wall_s[0].second, r.total_seconds);
  EXPECT_EQ(r.projected_wall_s.back().first, 64);
  EXPECT_DOUBLE_EQ(r.projected_wall_s.back().second, r.critical_path_s);
  const std::string json = ReportJson(r);
  EXPECT_NE(json.find("\"after_tasks_share\": 0.5,"), std::string::npos)
      << json;
  EXPECT_NE(json.find("\"depends\": [0, 3]"), std::string::npos) << json;
  // The chain: kernel 0, leaf 0.0, merge cluster 0, the two assembly steps.
  EXPECT_EQ(r.critical_path_rows, (std::vector<int>{0, 3, 5, 6, 7}));
  EXPECT_NE(json.find("\"workers\": 2, \"critical_path\": [0, 3, 5, 6, 7]"),
            std::string::npos)
      << json;
}

TEST(SummarizeTimeline, ReusedTasksCountNothing) {
  // A resumed run: the four tasks reused at 2 s, the merges and the
  // assembly run again.
  TmrMapperReport r = TwoKernelRun();
  for (int t = 0; t < 6; ++t) {
    r.tasks[t].start_s = 2;
    r.tasks[t].reused = t < 4;
  }
  r.tasks[6].start_s = 3;
  r.tasks[7].start_s = 13;
  r.total_seconds = 19;
  SummarizeTimeline(2, &r);
  EXPECT_DOUBLE_EQ(r.tasks_end_s, 3);
  EXPECT_DOUBLE_EQ(r.critical_path_s, 2 + 1 + 10 + 5 + 1);
  // Reused tasks take no time: the chain is a reused kernel, its cluster
  // merge (the first of two equally long) and the assembly.
  EXPECT_EQ(r.critical_path_rows, (std::vector<int>{1, 4, 6, 7}));
}

TEST(SummarizeTimeline, PartsSideBySideShrinkWithMoreWorkers) {
  // The last refinement (8 s on two workers) adjusted four blocks of 3 s
  // side by side in 6 s of it; its other 2 s ran on one thread.
  TmrMapperReport r = TwoKernelRun();
  r.tasks.back().seconds = 8;
  r.tasks.back().part_seconds = {3, 3, 3, 3};
  r.tasks.back().parts_wall_s = 6;
  r.total_seconds = 35;
  SummarizeTimeline(2, &r);
  EXPECT_DOUBLE_EQ(r.projected_wall_s[0].second, r.total_seconds);
  // With four workers or more, the blocks take 3 s instead of 6.
  EXPECT_DOUBLE_EQ(r.projected_wall_s[1].second, r.total_seconds - 3);
  EXPECT_DOUBLE_EQ(r.critical_path_s, 2 + 8 + 5 + 1 + 10 + 2 + 3 + 1);
  EXPECT_NE(ReportJson(r).find("\"part_seconds\": [3, 3, 3, 3]"),
            std::string::npos);
}

TEST(SummarizeTimeline, NoTimelineNoShare) {
  TmrMapperReport r;
  r.total_seconds = 10;
  EXPECT_NE(ReportJson(r).find("\"after_tasks_share\": 0,"), std::string::npos);
}

}  // namespace
}  // namespace tmr
