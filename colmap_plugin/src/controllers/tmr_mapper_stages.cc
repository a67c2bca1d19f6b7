// Copyright (c) 2026, the tmr authors. BSD-3-Clause.
#include "controllers/tmr_mapper_stages.h"

#include <chrono>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <sstream>
#include <string>
#include <unordered_map>
#include <unordered_set>

#include "controllers/tmr_mapper_options.h"
#include "io/task_database.h"
#include "merge/cluster_merge.h"
#include "merge/scene_assembly.h"
#include "sfm/reconstruction_task.h"
#include "tmr/io/atomic_file.h"
#include "tmr/util/process.h"

namespace tmr {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

std::string TreeJson(const TmrTree& tree) {
  std::ostringstream json;
  WriteTmrTreeJson(tree, json);
  return json.str();
}

}  // namespace

TmrMapperStages::TmrMapperStages(const TmrMapperOptions& options)
    : o_(options),
      budget_(ResolveMemoryBudget(options.memory_budget)),
      work_(fs::path(options.output_path) / ".tmr_work") {}

bool TmrMapperStages::Plan(TmrMapperReport* report, bool one_process,
                           const Progress& progress, std::string* error) {
  DatabasePartition partition;
  try {
    partition = PartitionDatabase(o_.database_path, o_.match_graph, o_.tree);
  } catch (const DatabaseError&) {
    throw;
  } catch (const std::runtime_error& e) {  // no images
    return Fail(e.what(), error);
  }
  const MatchGraph& graph = partition.graph;
  if (!CheckKeypointsAndCameras(o_.database_path, error)) return false;
  if (const int rigs = CountMultiCameraRigs(o_.database_path);
      rigs > 0 && progress) {
    progress("the database has " + std::to_string(rigs) +
             " rig(s) of several cameras: tmr maps their images as "
             "independent cameras (it does not use rig constraints yet)");
  }
  if (graph.NumPairs() == 0)
    return Fail("the database has no verified image pairs", error);
  tree_ = std::move(partition.tree);
  report->num_images = graph.NumImages();
  report->partition_seconds = partition.seconds;
  if (progress) {
    progress("partition: " + std::to_string(tree_.kernels.size()) +
             " kernels (" + DescribeKernels(tree_) + "), " +
             std::to_string(tree_.unclustered.size()) +
             " unclustered images (" +
             std::to_string(report->partition_seconds) + " s)");
  }
  if (tree_.kernels.empty())
    return Fail("the partition found no kernel", error);
  // The kernel and leaf tasks a killed run finished are reused when the
  // database, the partition and the options of the tasks are the same.
  TmrTree untimed = tree_;
  untimed.timing = {};
  if (!work_.Open(RunFingerprint(o_, TreeJson(untimed)), o_.resume))
    return Fail("cannot write in '" + work_.folder().string() + "'", error);
  if (work_.resuming() && progress) {
    progress("resuming: reusing the tasks an earlier run finished in " +
             work_.folder().string());
  }
  EstimateMemory(graph, one_process);
  if (!CheckMemory(one_process, progress, error)) return false;
  std::ostringstream plan;
  plan << std::fixed << std::setprecision(0);
  for (const TmrMapperTask& task : PlannedTasks()) {
    plan << task.id << " " << task.num_images << " " << task.num_base_images
         << " " << task.memory_mib << "\n";
  }
  plan << GroupPlanLines();
  plan << "merge " << graph.NumImages() << " 0 " << MergeMemoryMiB() << "\n";
  const fs::path out(o_.output_path);
  if (!WriteTmrTreeJsonFile(tree_, o_.output_path) ||
      !WriteFileAtomically((out / "plan.txt").string(), plan.str())) {
    return Fail(
        "cannot write tree.json and plan.txt in '" + o_.output_path + "'",
        error);
  }
  return true;
}

bool TmrMapperStages::Load(std::string* error) {
  const fs::path out(o_.output_path);
  const std::string tree_path = TmrTreeJsonPath(o_.output_path);
  std::ifstream in(tree_path);
  if (!in || !fs::exists(out / "plan.txt")) {
    return Fail("no plan in '" + o_.output_path +
                    "' (run `tmr_mapper partition` first)",
                error);
  }
  std::vector<std::string> names;
  const std::vector<MatchGraphImage> images =
      ReadDatabaseImages(o_.database_path);
  for (const MatchGraphImage& image : images) names.push_back(image.name);
  try {
    tree_ = ReadTmrTreeJson(in, names);
  } catch (const std::exception& e) {
    return Fail("cannot read '" + tree_path + "': " + e.what(), error);
  }
  for (const MatchGraphImage& image : images)
    tree_.image_ids.push_back(image.image_id);
  if (!ReadPlanMemory(error)) return false;
  TmrTree untimed = tree_;
  untimed.timing = {};
  if (!work_.Attach(RunFingerprint(o_, TreeJson(untimed)))) {
    return Fail("the plan in '" + o_.output_path +
                    "' was made from another database or with other "
                    "options; make it again (tmr_mapper partition)",
                error);
  }
  return true;
}

std::vector<TmrMapperTask> TmrMapperStages::Tasks() const {
  std::vector<TmrMapperTask> tasks = PlannedTasks();
  for (TmrMapperTask& task : tasks) {
    ReconstructionTaskResult result;
    task.finished = work_.Finished(Model(task), &result);
  }
  return tasks;
}

std::vector<TmrMapperTask> TmrMapperStages::PlannedTasks() const {
  std::vector<TmrMapperTask> tasks;
  for (int k = 0; k < static_cast<int>(tree_.kernels.size()); ++k) {
    const TmrKernelNode& node = tree_.kernels[k];
    tasks.push_back({"kernel." + std::to_string(k), k, -1,
                     static_cast<int>(node.kernel_images.size()), 0, false});
  }
  for (int k = 0; k < static_cast<int>(tree_.kernels.size()); ++k) {
    const TmrKernelNode& node = tree_.kernels[k];
    for (int l = 0; l < static_cast<int>(node.leaf_clusters.size()); ++l) {
      tasks.push_back({"leaf." + std::to_string(k) + "." + std::to_string(l), k,
                       l,
                       static_cast<int>(node.leaf_clusters[l].size() +
                                        node.leaf_halos.at(l).size()),
                       static_cast<int>(node.kernel_images.size()), false});
    }
  }
  for (TmrMapperTask& task : tasks) {
    if (const auto it = memory_mib_.find(task.id); it != memory_mib_.end())
      task.memory_mib = it->second;
  }
  return tasks;
}

std::string TmrMapperStages::Model(const TmrMapperTask& task) const {
  return task.leaf < 0 ? work_.KernelModel(task.kernel)
                       : work_.LeafModel(task.kernel, task.leaf);
}

TmrMapperStages::KernelState TmrMapperStages::ReadKernelState(int k) const {
  KernelState state;
  ReconstructionTaskResult result;
  state.finished = work_.Finished(work_.KernelModel(k), &result);
  state.success = state.finished && result.success;
  state.num_registered = result.num_registered;
  for (const std::string& path : result.part_models) {
    colmap::Reconstruction part;
    part.ReadBinary(path);
    for (const colmap::image_t id : part.RegImageIds())
      state.part_images.push_back(id);
  }
  return state;
}

TmrTaskReport TmrMapperStages::Row(const TmrMapperTask& task,
                                   const ReconstructionTaskResult& result,
                                   bool reused,
                                   const KernelState& kernel) const {
  TmrTaskReport row;
  row.name = task.leaf < 0 ? "kernel " + std::to_string(task.kernel)
                           : "leaf " + std::to_string(task.kernel) + "." +
                                 std::to_string(task.leaf);
  row.num_images = task.num_images;
  row.num_registered = result.num_registered;
  if (task.leaf >= 0) {
    // A leaf task registers the kernel images its kernel task left too;
    // its own count is what it adds to the kernel's model.
    const int base =
        task.num_base_images - static_cast<int>(kernel.part_images.size());
    row.num_images += base - kernel.num_registered;
    row.num_registered -= kernel.num_registered;
  }
  row.seconds = result.seconds;
  row.success = result.success;
  row.message = result.message;
  row.reused = reused;
  if (!result.part_models.empty()) {
    row.message += "; the rest in " +
                   std::to_string(result.part_models.size()) +
                   " more models of " +
                   std::to_string(result.num_registered_in_parts) + " images";
  }
  return row;
}

bool TmrMapperStages::RunTask(const TmrMapperTask& task, int num_threads,
                              TmrTaskReport* row, std::string* error) const {
  colmap::IncrementalPipelineOptions mapper = ColmapOptions(o_, num_threads);
  mapper.ba_global_frames_ratio = o_.task.ba_global_ratio;
  mapper.ba_global_points_ratio = o_.task.ba_global_ratio;
  const TmrKernelNode& node = tree_.kernels.at(task.kernel);
  const std::string model = Model(task);
  std::vector<uint32_t> images;
  std::vector<std::pair<int, int>> pairs;
  std::string base_model;
  std::vector<colmap::image_t> halo;
  KernelState kernel;  // a leaf task's kernel
  if (task.leaf < 0) {
    // The exemplar first with COLMAP's choice of a second image (most
    // matches, wide enough baseline), then with ours.
    images = ImageIdsOf(tree_, node.kernel_images);
    pairs.emplace_back(tree_.image_ids[node.exemplar], -1);
    for (const int second : node.second_images) {
      pairs.emplace_back(tree_.image_ids[node.exemplar],
                         tree_.image_ids[second]);
    }
  } else {
    kernel = ReadKernelState(task.kernel);
    if (!kernel.finished) {
      return Fail("task " + task.id + " needs kernel." +
                      std::to_string(task.kernel) + " finished first",
                  error);
    }
    if (!kernel.success) {
      ReconstructionTaskResult failed;
      failed.message = "its kernel task failed";
      SaveTaskResult(failed, model + ".result");
      *row = Row(task, failed, false, kernel);
      return true;
    }
    // The kernel images, except those a part model of the kernel holds
    // (no image in two models), and the leaf's: the leaf task may also
    // register kernel images its kernel task left. The leaf's share of the
    // cluster's halo (images of neighbouring clusters) is registered here
    // too, so that the cluster models share cameras and points when the
    // tasks end.
    const std::unordered_set<uint32_t> parts(kernel.part_images.begin(),
                                             kernel.part_images.end());
    const std::vector<uint32_t> all = ImageIdsOf(tree_, TaskImages(task));
    for (size_t i = 0; i < all.size(); ++i)
      if (i >= node.kernel_images.size() || !parts.count(all[i]))
        images.push_back(all[i]);
    halo = ImageIdsOf(tree_, node.leaf_halos.at(task.leaf));
    base_model = work_.KernelModel(task.kernel);
    mapper.fix_existing_frames = o_.task.fix_base_in_leaves;
  }
  const MatchConsistencyOptions kernel_check;
  bool reused = false;
  const auto result = work_.RunOrReuse(
      model, o_.database_path, images,
      [&](const std::string& db) {
        return RunReconstructionTask(
            mapper, db, base_model, pairs,
            o_.task.check_kernels ? &kernel_check : nullptr, model, halo);
      },
      &reused, error);
  if (!result) return false;
  *row = Row(task, *result, reused, kernel);
  return true;
}

std::optional<TmrTaskReport> TmrMapperStages::FinishedTaskRow(
    const TmrMapperTask& task) const {
  ReconstructionTaskResult result;
  if (!work_.Finished(Model(task), &result)) return std::nullopt;
  return Row(task, result, /*reused=*/false,
             task.leaf < 0 ? KernelState() : ReadKernelState(task.kernel));
}

std::shared_ptr<const colmap::DatabaseCache> TmrMapperStages::LoadCache(
    std::string* error) const {
  return LoadTaskDatabaseCache(o_.database_path, tree_.image_ids,
                               work_.MergeDatabase(), o_.mapper.min_num_matches,
                               o_.mapper.ignore_watermarks, error);
}

}  // namespace tmr
