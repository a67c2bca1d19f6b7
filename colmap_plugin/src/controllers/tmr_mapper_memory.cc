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

}  // namespace

double TmrMapperStages::LargestGroupMiB() const {
  double mib = 0.0;
  for (const ClusterGroup& group : groups_)
    mib = std::max(mib, group.memory_mib);
  return mib;
}

int TmrMapperStages::LargestGroupImages() const {
  int images = 0;
  for (const ClusterGroup& group : groups_)
    images = std::max(images, group.num_images);
  return images;
}

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

void TmrMapperStages::EstimateMemory(const MatchGraph& graph,
                                     bool one_process) {
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
  // A staged plan made with the default budget (maybe on a login node)
  // does not split the merge for memory: the merge job may get more.
  PlanGroups(graph, /*for_memory=*/one_process || o_.memory_budget > 0);
}

bool TmrMapperStages::ReadPlanMemory(std::string* error) {
  const std::string path = (fs::path(o_.output_path) / "plan.txt").string();
  std::ifstream plan(path);
  std::string line;
  memory_mib_.clear();
  groups_.clear();
  seam_images_.clear();
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
    bool group_line = false, bad = false;
    try {
      group_line = ReadGroupPlanLine(id, images, mib, &fields);
    } catch (const std::exception&) {  // a number that does not read
      bad = true;
    }
    if (bad || (!fields.eof() && fields.fail())) {
      return Fail("cannot read '" + path + "' (line '" + line.substr(0, 60) +
                      "'); make the plan again (tmr_mapper partition)",
                  error);
    }
    if (!group_line) memory_mib_[id] = mib;
  }
  if (!GroupsFitTheTree()) {
    return Fail("the groups of the merge stage in '" + path +
                    "' do not fit its tree; make the plan again (tmr_mapper "
                    "partition)",
                error);
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
  // By parts, each group's merge loads its own correspondences after the
  // tasks.
  const double beside =
      one_process && groups_.empty() ? correspondences_mib_ : 0.0;
  if (progress) {
    std::string line = "memory: budget " + GiBText(budget.mib) + " (" +
                       budget.source + "); expected peaks: ";
    if (largest != tasks.end()) {
      line += "tasks up to " + GiBText(largest->memory_mib) + " (" +
              largest->id + ", " +
              std::to_string(largest->num_images + largest->num_base_images) +
              " images), ";
    }
    if (one_process && groups_.empty())
      line += "correspondences of all images " + GiBText(beside) + ", ";
    if (groups_.empty()) {
      line += "merge stage " + GiBText(MergeMemoryMiB());
    } else {
      const bool capped =
          o_.merge.max_group_images > 0 &&
          static_cast<int>(tree_.image_ids.size()) > o_.merge.max_group_images;
      line +=
          std::string("merge stage by parts (") +
          (capped ? "--Tmr.merge_max_group_images" : "over the budget whole") +
          "): " + std::to_string(groups_.size()) +
          " groups of clusters up to " + GiBText(LargestGroupMiB()) +
          ", their join " + GiBText(MergeMemoryMiB());
    }
    progress(line);
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
  const std::string warning = MergeOverBudgetWarning(
      std::max(MergeMemoryMiB(), LargestGroupMiB()), budget);
  if (progress && !warning.empty()) progress(warning);
  return true;
}

}  // namespace tmr
