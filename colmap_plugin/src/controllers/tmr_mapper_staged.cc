// Copyright (c) 2026, the tmr authors. BSD-3-Clause.
// The staged entry points of tmr_mapper (tmr/colmap/tmr_mapper.h): plan,
// one task, one group of a merge stage by parts, the merge stage; each a
// process of its own on a batch scheduler (docs/distributed.md).
#include <algorithm>
#include <chrono>
#include <mutex>
#include <numeric>

#include "controllers/memory_budget.h"
#include "controllers/tmr_mapper_run.h"
#include "controllers/tmr_mapper_stages.h"
#include "tmr/colmap/tmr_mapper.h"
#include "tmr/util/process.h"

namespace tmr {
namespace {

using Clock = std::chrono::steady_clock;

// The staged plan of `stages`: its tasks, the groups of a merge stage by
// parts, with their state on disk.
TmrMapperPlan PlanOf(const TmrMapperStages& stages) {
  TmrMapperPlan plan{stages.Tasks(),
                     static_cast<int>(stages.tree().image_ids.size()),
                     stages.MergeMemoryMiB(),
                     {}};
  const auto& groups = stages.cluster_groups();
  for (int g = 0; g < static_cast<int>(groups.size()); ++g) {
    plan.merge_groups.push_back(
        {"merge." + std::to_string(g), groups[g].num_images,
         stages.UnfinishedTaskOfGroup(g, plan.tasks).empty(),
         stages.GroupMerged(g), groups[g].memory_mib});
  }
  return plan;
}

}  // namespace

bool PlanTmrMapper(const TmrMapperOptions& options, TmrMapperPlan* plan,
                   std::string* error,
                   const std::function<void(const std::string&)>& progress) {
  TmrMapperOptions effective;
  if (!PrepareTmrMapper(options, &effective, error)) return false;
  TmrMapperStages stages(effective);
  TmrMapperReport report;
  if (!stages.Plan(&report, /*one_process=*/false, progress, error))
    return false;
  *plan = PlanOf(stages);
  return true;
}

bool ReadTmrMapperPlan(const TmrMapperOptions& options, TmrMapperPlan* plan,
                       std::string* error) {
  TmrMapperOptions effective;
  if (!PrepareTmrMapper(options, &effective, error)) return false;
  TmrMapperStages stages(effective);
  if (!stages.Load(error)) return false;
  *plan = PlanOf(stages);
  return true;
}

bool RunTmrMapperTask(const TmrMapperOptions& options,
                      const std::string& task_id, TmrTaskReport* report,
                      std::string* error) {
  TmrMapperOptions effective;
  if (!PrepareTmrMapper(options, &effective, error)) return false;
  TmrMapperStages stages(effective);
  if (!stages.Load(error)) return false;
  for (const TmrMapperTask& task : stages.Tasks()) {
    if (task.id == task_id)
      return stages.RunTask(task, TmrMapperThreads(effective), report, error);
  }
  *error = "the plan has no task '" + task_id + "'";
  return false;
}

bool MergeTmrMapper(const TmrMapperOptions& options, TmrMapperReport* report,
                    std::string* error,
                    const std::function<void(const std::string&)>& progress) {
  const auto start = Clock::now();
  TmrMapperOptions effective;
  if (!PrepareTmrMapper(options, &effective, error)) return false;
  TmrMapperStages stages(effective);
  if (!stages.Load(error)) return false;
  *report = TmrMapperReport();
  report->num_images = static_cast<int>(stages.tree().image_ids.size());
  std::vector<std::string> unfinished;
  for (const TmrMapperTask& task : stages.Tasks()) {
    if (const auto row = stages.FinishedTaskRow(task)) {
      report->tasks.push_back(*row);
    } else {
      unfinished.push_back(task.id);
    }
  }
  if (!unfinished.empty()) {
    *error = std::to_string(unfinished.size()) + " tasks have not finished (" +
             unfinished.front() + (unfinished.size() > 1 ? ", ..." : "") +
             "); run them first (tmr_mapper run_task)";
    return false;
  }
  const MemoryBudget& budget = stages.budget();
  if (progress) {
    const size_t num_groups = stages.cluster_groups().size();
    progress("memory: budget " + GiBText(budget.mib) + " (" + budget.source +
             "); the merge stage is expected to need " +
             (num_groups == 0
                  ? GiBText(stages.MergeMemoryMiB())
                  : "up to " + GiBText(stages.LargestGroupMiB()) + " in " +
                        std::to_string(num_groups) +
                        " groups of clusters merged apart, " +
                        GiBText(stages.MergeMemoryMiB()) + " to join them"));
    // What this process will run: the groups not merged yet (none in a
    // join job after the groups' jobs), then the join.
    double need = stages.MergeMemoryMiB();
    for (int g = 0; g < static_cast<int>(num_groups); ++g) {
      if (!stages.GroupMerged(g))
        need = std::max(need, stages.cluster_groups()[g].memory_mib);
    }
    const std::string warning = MergeOverBudgetWarning(need, budget);
    if (!warning.empty()) progress(warning);
  }
  std::mutex mutex;
  auto note = [&](const std::string& line) {
    std::lock_guard<std::mutex> lock(mutex);
    if (progress) progress(line);
  };
  auto record = [&](TmrTaskReport row) {
    std::lock_guard<std::mutex> lock(mutex);
    const ProcessMemory memory = ReadProcessMemory();
    row.rss_mib = memory.rss_mib;
    row.peak_mib = memory.peak_mib;
    report->tasks.push_back(row);
    if (progress) progress(row.name + ": " + row.message);
  };
  const int threads = TmrMapperThreads(effective);
  const int num_groups = static_cast<int>(stages.cluster_groups().size());
  if (num_groups > 0) {
    // By parts: each group within the budget, one after the other, then
    // the join.
    for (int g = 0; g < num_groups; ++g)
      if (!stages.MergeGroup(g, threads, record, note, error)) return false;
    if (!stages.JoinGroups(threads, record, note, report, error)) return false;
  } else {
    const auto cache = stages.LoadCache(error);
    if (!cache) return false;
    std::vector<int> kernels(stages.tree().kernels.size());
    std::iota(kernels.begin(), kernels.end(), 0);
    if (!stages.AssembleAndWrite(
            stages.MergeClusters(kernels, cache, threads, record, note), cache,
            threads, record, progress, report, error))
      return false;
  }
  FinishTmrMapper(effective, stages, start, /*timeline=*/false, progress,
                  report);
  return true;
}

bool MergeTmrMapperGroup(
    const TmrMapperOptions& options, const std::string& group_id,
    std::string* error,
    const std::function<void(const std::string&)>& progress) {
  TmrMapperOptions effective;
  if (!PrepareTmrMapper(options, &effective, error)) return false;
  TmrMapperStages stages(effective);
  if (!stages.Load(error)) return false;
  const int num_groups = static_cast<int>(stages.cluster_groups().size());
  for (int g = 0; g < num_groups; ++g) {
    if ("merge." + std::to_string(g) != group_id) continue;
    std::mutex mutex;
    auto note = [&](const std::string& line) {
      std::lock_guard<std::mutex> lock(mutex);
      if (progress) progress(line);
    };
    auto record = [&](const TmrTaskReport& row) {
      note(row.name + ": " + row.message);
    };
    return stages.MergeGroup(g, TmrMapperThreads(effective), record, note,
                             error);
  }
  *error = "the plan has no merge group '" + group_id + "'" +
           (num_groups == 0
                ? " (its merge stage fits the memory budget whole: tmr_mapper "
                  "merge)"
                : "");
  return false;
}

}  // namespace tmr
