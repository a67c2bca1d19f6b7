// Copyright (c) 2026, the tmr authors. BSD-3-Clause.
// TmrMapperStages' images of each task, the expected memory of every step
// (controllers/memory_budget.h) and the check of the plan against
// options.memory_budget.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <numeric>
#include <sstream>

#include "controllers/memory_budget.h"
#include "controllers/tmr_mapper_stages.h"
#include "tmr/partition/merge_groups.h"

namespace tmr {
namespace {

namespace fs = std::filesystem;

bool Fail(const std::string& message, std::string* error) {
  *error = message;
  return false;
}

}  // namespace

double TmrMapperStages::MergeMemoryMiB() const {
  const auto it = memory_mib_.find("merge");
  return it == memory_mib_.end() ? 0.0 : it->second;
}

std::vector<int> TmrMapperStages::TaskImages(const TmrMapperTask& task) const {
  const TmrKernelNode& node = tree_.kernels.at(task.kernel);
  std::vector<int> images = node.kernel_images;
  if (task.leaf >= 0) {
    for (const auto* part :
         {&node.leaf_clusters.at(task.leaf), &node.leaf_halos.at(task.leaf)})
      images.insert(images.end(), part->begin(), part->end());
  }
  return images;
}

void TmrMapperStages::EstimateMemory(const MatchGraph& graph) {
  memory_mib_.clear();
  for (const TmrMapperTask& task : PlannedTasks())
    memory_mib_[task.id] = TaskPeakMiB(LoadOfImages(graph, TaskImages(task)));
  std::vector<int> all(graph.NumImages());
  std::iota(all.begin(), all.end(), 0);
  const MemoryLoad scene = LoadOfImages(graph, all);
  memory_mib_["merge"] = MergePeakMiB(scene, o_.refinement.points_per_image,
                                      o_.refinement.max_block_images);
  correspondences_mib_ = CorrespondencesMiB(scene);
  cluster_mib_.clear();
  for (const TmrKernelNode& node : tree_.kernels)
    cluster_mib_.push_back(
        TaskPeakMiB(LoadOfImages(graph, node.cluster_images)));
  // The groups of clusters a merge stage by parts would take (issue 43,
  // item 2): each cluster with its halo, at its own merge stage's peak.
  merge_groups_.clear();
  if (MergeMemoryMiB() <= budget_.mib) return;
  std::vector<int> cluster_of(graph.NumImages(), -1);
  std::vector<double> cost;
  for (int k = 0; k < static_cast<int>(tree_.kernels.size()); ++k) {
    const TmrKernelNode& node = tree_.kernels[k];
    std::vector<int> images = node.cluster_images;
    for (const int i : node.cluster_images) cluster_of[i] = k;
    for (const auto& halo : node.leaf_halos)
      images.insert(images.end(), halo.begin(), halo.end());
    cost.push_back(MergePeakMiB(LoadOfImages(graph, images),
                                o_.refinement.points_per_image,
                                o_.refinement.max_block_images));
  }
  for (const std::vector<int>& group :
       GroupClusters(cost, LinkClusters(graph, cluster_of), budget_.mib)) {
    double mib = 0.0;
    for (const int k : group) mib += cost[k];
    merge_groups_.push_back(mib);
  }
}

bool TmrMapperStages::ReadPlanMemory(std::string* error) {
  const std::string path = (fs::path(o_.output_path) / "plan.txt").string();
  std::ifstream plan(path);
  std::string line;
  memory_mib_.clear();
  while (std::getline(plan, line)) {
    std::istringstream fields(line);
    std::string id;
    int images = 0, base = 0;
    double mib = 0.0;  // unknown in a plan made before it was written
    if (!(fields >> id >> images >> base)) {
      return Fail("cannot read '" + path + "' (line '" + line +
                      "'); make the plan again (tmr_mapper partition)",
                  error);
    }
    fields >> mib;
    memory_mib_[id] = mib;
  }
  return true;
}

bool TmrMapperStages::CheckMemory(bool one_process, const Progress& progress,
                                  std::string* error) const {
  const MemoryBudget& budget = budget_;
  const std::vector<TmrMapperTask> tasks = PlannedTasks();
  const auto largest = std::max_element(
      tasks.begin(), tasks.end(),
      [](const auto& a, const auto& b) { return a.memory_mib < b.memory_mib; });
  const double beside = one_process ? correspondences_mib_ : 0.0;
  if (progress) {
    std::string line = "memory: budget " + GiBText(budget.mib) + " (" +
                       budget.source + "); expected peaks: ";
    if (largest != tasks.end()) {
      line += "tasks up to " + GiBText(largest->memory_mib) + " (" +
              largest->id + ", " +
              std::to_string(largest->num_images + largest->num_base_images) +
              " images), ";
    }
    if (one_process)
      line += "correspondences of all images " + GiBText(beside) + ", ";
    progress(line + "merge stage " + GiBText(MergeMemoryMiB()));
  }
  if (largest != tasks.end() && largest->memory_mib + beside > budget.mib) {
    const std::string need =
        "about " + GiBText(largest->memory_mib) + " for its " +
        std::to_string(largest->num_images + largest->num_base_images) +
        " images";
    // A staged plan made without a budget may be made on a smaller machine
    // (a login node) than the ones that run its tasks.
    if (!one_process && o_.memory_budget <= 0) {
      if (progress) {
        progress("warning: task " + largest->id + " needs " + need +
                 ", more than this machine's budget of " + GiBText(budget.mib) +
                 "; run it where it fits");
      }
    } else {
      return Fail("the memory budget of " + GiBText(budget.mib) + " (" +
                      budget.source + ") is too small for task " + largest->id +
                      ": " + need +
                      (one_process ? ", beside " + GiBText(beside) +
                                         " of correspondences of all images"
                                   : "") +
                      "; give --Tmr.memory_budget " +
                      std::to_string(static_cast<int>(
                          std::ceil((largest->memory_mib + beside) / 1024.0))) +
                      " or more",
                  error);
    }
  }
  const std::string warning = MergeOverBudgetWarning(MergeMemoryMiB(), budget);
  if (progress && !warning.empty()) {
    const double largest_group =
        merge_groups_.empty()
            ? 0.0
            : *std::max_element(merge_groups_.begin(), merge_groups_.end());
    progress(warning + " (by parts: " + std::to_string(merge_groups_.size()) +
             " groups of clusters, the largest about " +
             GiBText(largest_group) + ")");
  }
  return true;
}

}  // namespace tmr
