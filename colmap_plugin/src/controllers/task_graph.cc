// Copyright (c) 2026, the tmr authors. BSD-3-Clause.
#include "controllers/task_graph.h"

#include <algorithm>
#include <condition_variable>
#include <exception>
#include <mutex>
#include <stdexcept>
#include <thread>

namespace tmr {

int TaskGraph::Add(Task task) {
  for (const int d : task.depends) {
    if (d < 0 || d >= NumTasks())
      throw std::invalid_argument("TaskGraph: unknown dependency");
  }
  if (!task.run) throw std::invalid_argument("TaskGraph: task without run");
  tasks_.push_back(std::move(task));
  return NumTasks() - 1;
}

namespace {

// Whether ready task a goes before b: higher priority, ties to the earlier
// task.
bool Before(const std::vector<double>& priority, int a, int b) {
  return priority[a] > priority[b] || (priority[a] == priority[b] && a < b);
}

// The position in `ready` of the task of highest priority that `fits`, or
// -1.
template <typename Fits>
int BestFitting(const std::vector<double>& priority,
                const std::vector<int>& ready, Fits fits) {
  int best = -1;
  for (int i = 0; i < static_cast<int>(ready.size()); ++i) {
    if (fits(ready[i]) && (best < 0 || Before(priority, ready[i], ready[best])))
      best = i;
  }
  return best;
}

// Removes from `ready` (not empty) and returns its task of highest
// priority.
int TakeHighestPriority(const std::vector<double>& priority,
                        std::vector<int>* ready) {
  const int best = BestFitting(priority, *ready, [](int) { return true; });
  const int t = (*ready)[best];
  ready->erase(ready->begin() + best);
  return t;
}

}  // namespace

void TaskGraph::Run(int num_workers, double memory_budget) {
  if (num_workers < 1)
    throw std::invalid_argument("TaskGraph: needs at least one worker");
  const int n = NumTasks();
  std::vector<int> waiting_on(n, 0);
  std::vector<std::vector<int>> dependents(n);
  for (int t = 0; t < n; ++t) {
    waiting_on[t] = static_cast<int>(tasks_[t].depends.size());
    for (const int d : tasks_[t].depends) dependents[d].push_back(t);
  }
  std::vector<double> costs(n);
  std::vector<std::vector<int>> depends(n);
  for (int t = 0; t < n; ++t) {
    costs[t] = tasks_[t].cost;
    depends[t] = tasks_[t].depends;
  }
  const std::vector<double> priority = PathPriorities(costs, depends);
  std::vector<int> ready;
  for (int t = 0; t < n; ++t)
    if (waiting_on[t] == 0) ready.push_back(t);

  std::mutex mutex;
  std::condition_variable changed;
  int running = 0, finished = 0;
  double memory_in_use = 0.0;
  auto fits = [&](int t) {
    return memory_budget <= 0.0 || running == 0 ||
           memory_in_use + tasks_[t].memory <= memory_budget;
  };
  std::exception_ptr failure;
  auto worker = [&] {
    std::unique_lock<std::mutex> lock(mutex);
    while (true) {
      int next = -1;
      changed.wait(lock, [&] {
        next = BestFitting(priority, ready, fits);
        return next >= 0 || finished == n;
      });
      if (finished == n) return;
      const int t = ready[next];
      ready.erase(ready.begin() + next);
      ++running;
      memory_in_use += tasks_[t].memory;
      // The workers go to the tasks that can run now: those running and
      // the ready ones that fit beside them.
      const int share = running + static_cast<int>(std::count_if(
                                      ready.begin(), ready.end(), fits));
      const int threads = std::max(1, num_workers / std::max(1, share));
      lock.unlock();
      try {
        tasks_[t].run(threads);
      } catch (...) {
        // COLMAP reports some failures by throwing; keep the first, let the
        // other workers finish, and rethrow once all have joined.
        std::lock_guard<std::mutex> guard(mutex);
        if (!failure) failure = std::current_exception();
      }
      lock.lock();
      --running;
      memory_in_use -= tasks_[t].memory;
      ++finished;
      for (const int d : dependents[t])
        if (--waiting_on[d] == 0) ready.push_back(d);
      changed.notify_all();
    }
  };
  std::vector<std::thread> threads;
  for (int w = 0; w < std::min(num_workers, std::max(1, n)); ++w)
    threads.emplace_back(worker);
  for (std::thread& thread : threads) thread.join();
  if (failure) std::rethrow_exception(failure);
}

std::vector<double> PathPriorities(
    const std::vector<double>& costs,
    const std::vector<std::vector<int>>& depends) {
  // The costliest path from the task to the end of the graph. Dependencies
  // always have smaller ids, so one backward pass suffices.
  const int n = static_cast<int>(costs.size());
  std::vector<double> priority(costs);
  for (int t = n - 1; t >= 0; --t) {
    for (const int d : depends[t]) {
      if (d < 0 || d >= t)
        throw std::invalid_argument("PathPriorities: dependency order");
      priority[d] = std::max(priority[d], costs[d] + priority[t]);
    }
  }
  return priority;
}

double ScheduledWallTime(const std::vector<double>& seconds,
                         const std::vector<std::vector<int>>& depends,
                         int num_workers) {
  const int n = static_cast<int>(seconds.size());
  if (n == 0) return 0.0;
  const std::vector<double> priority = PathPriorities(seconds, depends);
  std::vector<double> end(n, 0.0);
  std::vector<int> waiting_on(n);
  std::vector<std::vector<int>> dependents(n);
  for (int t = 0; t < n; ++t) {
    waiting_on[t] = static_cast<int>(depends[t].size());
    for (const int d : depends[t]) dependents[d].push_back(t);
  }
  // Event simulation: a worker that frees up takes the ready task of the
  // highest priority (ties to the smaller id), as TaskGraph::Run does.
  const int workers = num_workers > 0 ? std::min(num_workers, n) : n;
  std::vector<double> free_at(workers, 0.0);
  std::vector<int> ready;
  for (int t = 0; t < n; ++t)
    if (waiting_on[t] == 0) ready.push_back(t);
  // Tasks started, by end time, whose dependents are not released yet.
  std::vector<int> running;
  double now = 0.0, wall = 0.0;
  int done = 0;
  while (done < n) {
    // Start what the free workers can take now.
    for (double& free : free_at) {
      if (free > now || ready.empty()) continue;
      const int t = TakeHighestPriority(priority, &ready);
      end[t] = now + seconds[t];
      free = end[t];
      running.push_back(t);
    }
    // Advance to the next end of a running task and release its dependents.
    if (running.empty())
      throw std::logic_error("ScheduledWallTime: nothing runs");
    const auto next =
        std::min_element(running.begin(), running.end(),
                         [&](int a, int b) { return end[a] < end[b]; });
    const int t = *next;
    running.erase(next);
    now = end[t];
    wall = std::max(wall, now);
    ++done;
    for (const int d : dependents[t])
      if (--waiting_on[d] == 0) ready.push_back(d);
  }
  return wall;
}

}  // namespace tmr
