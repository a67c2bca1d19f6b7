// Copyright (c) 2026, the tmr authors. BSD-3-Clause.
#include "controllers/task_graph.h"

#include <gtest/gtest.h>

#include <atomic>
#include <mutex>
#include <stdexcept>

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

TEST(TaskGraph, EmptyGraphReturns) {
  TaskGraph graph;
  graph.Run(3);
  SUCCEED();
}

}  // namespace
}  // namespace tmr
