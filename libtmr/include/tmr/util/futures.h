// Copyright (c) 2026, the tmr authors. BSD-3-Clause.
// Waiting for tasks run side by side (e.g. by colmap::ThreadPool::AddTask,
// whose Wait drops the tasks' exceptions).
#pragma once

#include <future>
#include <vector>

namespace tmr {

// Waits until every task of `tasks` has finished, then rethrows the first
// exception one of them threw (in their order): no task is left running on
// data the caller frees when it unwinds, and no failure is lost.
inline void WaitForAll(const std::vector<std::shared_future<void>>& tasks) {
  for (const std::shared_future<void>& task : tasks) task.wait();
  for (const std::shared_future<void>& task : tasks) task.get();
}

}  // namespace tmr
