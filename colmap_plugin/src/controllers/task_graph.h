// Copyright (c) 2026, the tmr authors. BSD-3-Clause.
#pragma once

#include <functional>
#include <string>
#include <vector>

namespace tmr {

// A dependency graph of tasks run on a fixed number of worker threads.
//
// tmr_mapper's reconstruction is a tree of independent units (paper Sec. 5):
// a leaf-cluster task needs only its own kernel's model, a cluster merge
// only its own leaves. Running them as a graph instead of in stages keeps
// every worker busy: the leaves of a small kernel start while a large kernel
// is still being reconstructed.
//
// Scheduling: among the tasks whose dependencies have finished, the one on
// the longest remaining path starts first: its priority is its own cost plus
// the largest priority among the tasks that depend on it (critical-path list
// scheduling; with no dependencies, longest-processing-time first). A kernel
// with large leaves thus starts before a lone large leaf, which unlocks work
// for the other workers sooner. A task is told how many threads it may use:
// the workers divided among the tasks that are running or ready, at least
// one, so that the last large task gets all cores.
//
// With a memory budget, a task starts only while the expected memory of the
// tasks running beside it and its own stay within it (the ready task of
// highest priority that fits; one that fits nowhere runs alone), so that
// workers wait rather than the machine swap or kill the run.
class TaskGraph {
 public:
  struct Task {
    std::string name;
    double cost = 1.0;         // relative work; larger starts first
    std::vector<int> depends;  // ids of tasks that must finish first
    std::function<void(int num_threads)> run;
    double memory = 0.0;  // expected peak memory while it runs (any unit)
  };

  // Returns the id of the new task; dependencies must already exist.
  int Add(Task task);

  int NumTasks() const { return static_cast<int>(tasks_.size()); }

  // Runs every task once, on `num_workers` threads, and returns when all
  // have finished. If a task throws, its dependents still run (they see
  // its missing output); the first exception is rethrown at the end.
  // `memory_budget` (the unit of Task::memory; <= 0: none) bounds the sum
  // of the running tasks' memory.
  void Run(int num_workers, double memory_budget = 0.0);

 private:
  std::vector<Task> tasks_;
};

// Critical-path priorities of a task graph whose dependencies have smaller
// ids: a task's own cost plus the largest priority among its dependents.
std::vector<double> PathPriorities(
    const std::vector<double>& costs,
    const std::vector<std::vector<int>>& depends);

// The wall time of tasks that take `seconds` each, run after `depends`
// (smaller ids) on `num_workers` workers with TaskGraph::Run's scheduling,
// the durations taken for the costs: a replay of a run's recorded task
// times on another number of cores. Each task keeps its duration whatever
// the workers (tmr_mapper runs every COLMAP step on one thread by default).
// num_workers <= 0: unlimited, the critical path.
double ScheduledWallTime(const std::vector<double>& seconds,
                         const std::vector<std::vector<int>>& depends,
                         int num_workers);

}  // namespace tmr
