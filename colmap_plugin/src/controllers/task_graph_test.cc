// Copyright (c) 2026, the tmr authors. BSD-3-Clause.
#include "controllers/task_graph.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <mutex>
#include <stdexcept>
#include <thread>

namespace tmr {
namespace {

TEST(TaskGraph, RunsEveryTaskAfterItsDependencies) {
  TaskGraph graph;
  std::mutex mutex;
  std::vector<int> order;
  auto record = [&](int id) {
    return [&, id](int) {
      std::lock_guard<std::mutex> lock(mutex);
      order.push_back(id);
    };
  };
  const int a = graph.Add({"a", 1.0, {}, record(0)});
  const int b = graph.Add({"b", 5.0, {}, record(1)});
  const int c = graph.Add({"c", 9.0, {a}, record(2)});
  graph.Add({"d", 1.0, {b, c}, record(3)});
  graph.Run(2);
  ASSERT_EQ(order.size(), 4u);
  auto position = [&](int id) {
    return std::find(order.begin(), order.end(), id) - order.begin();
  };
  EXPECT_LT(position(0), position(2));
  EXPECT_LT(position(1), position(3));
  EXPECT_LT(position(2), position(3));
}

TEST(TaskGraph, OneWorkerStartsTheCostliestReadyTaskFirst) {
  TaskGraph graph;
  std::vector<std::string> order;
  for (const double cost : {2.0, 7.0, 1.0, 7.0}) {
    graph.Add({"", cost, {}, [&order, cost](int) {
                 order.push_back(std::to_string(static_cast<int>(cost)));
               }});
  }
  graph.Run(1);
  EXPECT_EQ(order, (std::vector<std::string>{"7", "7", "2", "1"}));
}

TEST(TaskGraph, OneWorkerFollowsTheLongestPath) {
  // A kernel-like task (cost 3) whose dependent costs 10 goes before a lone
  // task of cost 8.
  TaskGraph graph;
  std::vector<std::string> order;
  auto record = [&order](const std::string& name) {
    return [&order, name](int) { order.push_back(name); };
  };
  graph.Add({"lone", 8.0, {}, record("lone")});
  const int kernel = graph.Add({"kernel", 3.0, {}, record("kernel")});
  graph.Add({"leaf", 10.0, {kernel}, record("leaf")});
  graph.Run(1);
  EXPECT_EQ(order, (std::vector<std::string>{"kernel", "leaf", "lone"}));
}

TEST(TaskGraph, TheLastTaskGetsAllWorkers) {
  TaskGraph graph;
  std::atomic<int> first_threads{0}, last_threads{0};
  const int first = graph.Add(
      {"first", 1.0, {}, [&](int threads) { first_threads = threads; }});
  graph.Add(
      {"last", 1.0, {first}, [&](int threads) { last_threads = threads; }});
  graph.Run(4);
  EXPECT_EQ(first_threads, 4);
  EXPECT_EQ(last_threads, 4);
}

TEST(TaskGraph, ConcurrentTasksShareTheWorkers) {
  TaskGraph graph;
  std::atomic<int> total{0};
  for (int i = 0; i < 4; ++i)
    graph.Add({"", 1.0, {}, [&](int threads) { total += threads; }});
  graph.Run(2);
  // With four ready tasks each starts with one of the two workers, except
  // possibly the last, which may find itself alone.
  EXPECT_GE(total, 4);
  EXPECT_LE(total, 5);
}

// Runs tasks of the given memory on `workers` threads within `budget`;
// returns the most memory the running tasks held at once.
double PeakMemoryOfRun(const std::vector<double>& memory, int workers,
                       double budget) {
  TaskGraph graph;
  std::mutex mutex;
  double in_use = 0.0, peak = 0.0;
  for (const double m : memory) {
    graph.Add({"",
               m,
               {},
               [&, m](int) {
                 {
                   std::lock_guard<std::mutex> lock(mutex);
                   in_use += m;
                   peak = std::max(peak, in_use);
                 }
                 std::this_thread::sleep_for(std::chrono::milliseconds(20));
                 std::lock_guard<std::mutex> lock(mutex);
                 in_use -= m;
               },
               m});
  }
  graph.Run(workers, budget);
  return peak;
}

TEST(TaskGraph, RunningTasksStayWithinTheMemoryBudget) {
  // Four workers, but only two tasks of 40 fit in 100 at once; a task of 30
  // fits beside one of 60.
  EXPECT_LE(PeakMemoryOfRun({40, 40, 40, 40, 40}, 4, 100), 100);
  EXPECT_LE(PeakMemoryOfRun({60, 30, 60, 30, 10}, 4, 100), 100);
}

TEST(TaskGraph, ATaskAboveTheBudgetRunsAlone) {
  EXPECT_EQ(PeakMemoryOfRun({150, 20, 20}, 3, 100), 150);
}

TEST(TaskGraph, AThrowingTaskEndsTheRunWithItsException) {
  TaskGraph graph;
  std::atomic<int> ran{0};
  const int failing = graph.Add({"failing", 1.0, {}, [](int) {
                                   throw std::runtime_error("task failed");
                                 }});
  graph.Add({"after", 1.0, {failing}, [&](int) { ++ran; }});
  graph.Add({"other", 1.0, {}, [&](int) { ++ran; }});
  EXPECT_THROW(graph.Run(2), std::runtime_error);
  EXPECT_EQ(ran, 2);
}

TEST(TaskGraph, AnEmptyGraphRunsNothingAndTakesNoTime) {
  TaskGraph graph;
  graph.Run(3);
  EXPECT_EQ(graph.NumTasks(), 0);
  EXPECT_TRUE(PathPriorities({}, {}).empty());
  EXPECT_EQ(ScheduledWallTime({}, {}, 3), 0.0);
  EXPECT_EQ(ScheduledWallTime({}, {}, 0), 0.0);
}

TEST(ScheduledWallTime, ReplaysTasksOnAnyNumberOfWorkers) {
  // Two kernels (4 s, 2 s), their leaves (3 s, 3 s; 1 s), a merge per
  // kernel (1 s) and a serial tail (2 s) after both merges.
  const std::vector<double> seconds = {4, 2, 3, 3, 1, 1, 1, 2};
  const std::vector<std::vector<int>> depends = {
      {}, {}, {0}, {0}, {1}, {0, 2, 3}, {1, 4}, {5, 6}};
  // Unlimited workers: the longest chain, kernel 0, a leaf, its merge, the
  // tail.
  EXPECT_DOUBLE_EQ(ScheduledWallTime(seconds, depends, 0), 4 + 3 + 1 + 2);
  EXPECT_DOUBLE_EQ(ScheduledWallTime(seconds, depends, 64), 10);
  // One worker: the sum.
  EXPECT_DOUBLE_EQ(ScheduledWallTime(seconds, depends, 1), 17);
  // Two workers: kernel 0 and kernel 1 start together; at 2 s the second
  // worker takes leaf 1.0, at 3 s merge 1; at 4 s both leaves of kernel 0
  // start, at 7 s its merge, at 8 s the tail.
  EXPECT_DOUBLE_EQ(ScheduledWallTime(seconds, depends, 2), 10);
}

TEST(ScheduledWallTime, BetweenTheCriticalPathAndOneWorker) {
  std::vector<double> seconds;
  std::vector<std::vector<int>> depends;
  for (int t = 0; t < 40; ++t) {
    seconds.push_back(1 + (t * 7) % 5);
    depends.push_back(t >= 3 ? std::vector<int>{t / 3} : std::vector<int>{});
  }
  const double path = ScheduledWallTime(seconds, depends, 0);
  double sum = 0.0;
  for (const double s : seconds) sum += s;
  EXPECT_DOUBLE_EQ(ScheduledWallTime(seconds, depends, 1), sum);
  for (const int workers : {2, 4, 8, 16}) {
    const double wall = ScheduledWallTime(seconds, depends, workers);
    EXPECT_LE(wall, sum);
    EXPECT_GE(wall, path);
  }
  // As many workers as tasks: every task starts when it is ready.
  EXPECT_DOUBLE_EQ(ScheduledWallTime(seconds, depends, 64), path);
}

}  // namespace
}  // namespace tmr
