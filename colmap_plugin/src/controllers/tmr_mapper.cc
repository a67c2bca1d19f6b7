// Copyright (c) 2026, the tmr authors. BSD-3-Clause.
#include "tmr/colmap/tmr_mapper.h"

#include <colmap/scene/database_cache.h>
#include <glog/logging.h>

#include <chrono>
#include <filesystem>
#include <mutex>
#include <sstream>
#include <thread>
#include <unordered_set>

#include "controllers/scene_assembly.h"
#include "controllers/task_graph.h"
#include "controllers/task_workspace.h"
#include "controllers/tmr_mapper_support.h"
#include "sfm/reconstruction_task.h"
#include "sfm/task_database.h"
#include "tmr/io/atomic_file.h"

namespace tmr {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

std::vector<uint32_t> Ids(const TmrTree& tree,
                          const std::vector<int>& vertices) {
  std::vector<uint32_t> ids;
  for (const int v : vertices) ids.push_back(tree.image_ids.at(v));
  return ids;
}

class TmrMapperRun {
 public:
  TmrMapperRun(const TmrMapperOptions& options, TmrMapperReport* report,
               const std::function<void(const std::string&)>& progress)
      : o_(options),
        report_(report),
        progress_(progress),
        work_(fs::path(o_.output_path) / ".tmr_work") {
    threads_ = o_.num_threads > 0
                   ? o_.num_threads
                   : std::max(1u, std::thread::hardware_concurrency());
  }

  bool Run(std::string* error) {
    const auto start = Clock::now();
    const MatchGraph graph = ReadMatchGraph(o_.database_path, o_.match_graph);
    if (graph.NumImages() == 0)
      return Fail("the database has no images", error);
    if (!CheckKeypointsAndCameras(o_.database_path, error)) return false;
    if (graph.NumPairs() == 0)
      return Fail("the database has no verified image pairs", error);
    tree_ = BuildTmrTree(graph, o_.tree);
    report_->num_images = graph.NumImages();
    report_->partition_seconds = SecondsSince(start);
    std::ostringstream json;
    WriteTmrTreeJson(tree_, json);
    // The kernel and leaf tasks a killed run finished are reused when the
    // database, the partition and the options of the tasks are the same.
    TmrTree untimed = tree_;
    untimed.timing = {};
    std::ostringstream partition;
    WriteTmrTreeJson(untimed, partition);
    if (!work_.Open(RunFingerprint(o_, partition.str()), o_.resume))
      return Fail("cannot write in '" + work_.folder().string() + "'", error);
    if (work_.resuming()) {
      Progress("resuming: reusing the tasks an earlier run finished in " +
               work_.folder().string());
    }
    if (!WriteFileAtomically((fs::path(o_.output_path) / "tree.json").string(),
                             json.str())) {
      return Fail("cannot write tree.json in '" + o_.output_path + "'", error);
    }
    Progress("partition: " + std::to_string(tree_.kernels.size()) +
             " kernels, " + std::to_string(tree_.unclustered.size()) +
             " unclustered images (" +
             std::to_string(report_->partition_seconds) + " s)");
    if (tree_.kernels.empty())
      return Fail("the partition found no kernel", error);

    if (!RunTaskGraph(error)) return false;
    SceneAssembler assembler(o_, cache_, work_.MergeDatabase(),
                             tree_.image_names, threads_,
                             [this](const TmrTaskReport& t) { Record(t); });
    const std::vector<std::shared_ptr<colmap::Reconstruction>> scenes =
        assembler.Assemble(clusters_);
    if (!WriteModels(scenes, error)) return false;
    report_->total_seconds = SecondsSince(start);
    WriteFileAtomically((fs::path(o_.output_path) / "report.json").string(),
                        ReportJson(*report_));
    if (!o_.keep_work) fs::remove_all(work_.folder());
    return true;
  }

 private:
  bool Fail(const std::string& message, std::string* error) {
    *error = message;
    return false;
  }

  void Progress(const std::string& line) {
    std::lock_guard<std::mutex> lock(mutex_);
    if (progress_) progress_(line);
  }

  // Reports a finished task; `weight` (images) drives the ETA of the task
  // graph, 0 for steps outside it.
  void Record(const TmrTaskReport& task, double weight = 0.0) {
    std::lock_guard<std::mutex> lock(mutex_);
    report_->tasks.push_back(task);
    done_weight_ += weight;
    if (!progress_) return;
    std::ostringstream line;
    line.precision(1);
    line << std::fixed << task.name << ": " << task.num_registered << "/"
         << task.num_images << " images in " << task.seconds << " s"
         << (task.success ? "" : ", " + task.message)
         << (task.reused ? " (finished by an earlier run)" : "");
    if (weight > 0 && done_weight_ < total_weight_) {
      const double elapsed = SecondsSince(graph_start_);
      line << "; ETA "
           << elapsed / done_weight_ * (total_weight_ - done_weight_) << " s";
    }
    progress_(line.str());
  }

  // Kernel, leaf and cluster-merge tasks as one graph: a leaf task waits
  // only for its kernel, a cluster merge only for its own leaves. Costs are
  // rough seconds per image measured on tmr_synth cities: about one per
  // image reconstructed, a leaf's fixed base a third of that, a merge a
  // tenth per image.
  bool RunTaskGraph(std::string* error) {
    const int num_kernels = static_cast<int>(tree_.kernels.size());
    kernel_ok_.assign(num_kernels, false);
    base_registered_.assign(num_kernels, 0);
    clusters_.assign(num_kernels, nullptr);
    TaskGraph graph;
    std::string cache_error;
    const int cache =
        graph.Add({"load correspondences", 1e12, {}, [&](int) {
                     cache_ = LoadTaskDatabaseCache(
                         o_.database_path, tree_.image_ids,
                         work_.MergeDatabase(), o_.mapper.min_num_matches,
                         o_.mapper.ignore_watermarks, &cache_error);
                   }});
    total_weight_ = done_weight_ = 0.0;
    for (int k = 0; k < num_kernels; ++k) {
      const TmrKernelNode& node = tree_.kernels[k];
      const double kernel_size = node.kernel_images.size();
      const int kernel = graph.Add(
          {"kernel", kernel_size, {}, [this, k](int t) { RunKernel(k, t); }});
      std::vector<int> merge_depends = {cache, kernel};
      total_weight_ += kernel_size;
      for (int l = 0; l < static_cast<int>(node.leaf_clusters.size()); ++l) {
        const double leaf_size = node.leaf_clusters[l].size();
        merge_depends.push_back(
            graph.Add({"leaf",
                       leaf_size + 0.3 * kernel_size,
                       {kernel},
                       [this, k, l](int t) { RunLeaf(k, l, t); }}));
        total_weight_ += leaf_size;
      }
      graph.Add({"merge", 0.1 * node.cluster_images.size(), merge_depends,
                 [this, k](int t) { MergeCluster(k, t); }});
    }
    graph_start_ = Clock::now();
    graph.Run(threads_);
    if (!cache_) return Fail(cache_error, error);
    clusters_.erase(std::remove(clusters_.begin(), clusters_.end(), nullptr),
                    clusters_.end());
    clusters_.insert(clusters_.end(), part_models_.begin(), part_models_.end());
    return true;
  }

  // COLMAP's mapper options for a kernel or leaf task.
  colmap::IncrementalMapperOptions TaskOptions(int num_threads) const {
    colmap::IncrementalMapperOptions options =
        ColmapOptions(o_.mapper, num_threads);
    options.ba_global_images_ratio = o_.task_ba_global_ratio;
    options.ba_global_points_ratio = o_.task_ba_global_ratio;
    return options;
  }

  void RunKernel(int k, int num_threads) {
    const TmrKernelNode& node = tree_.kernels[k];
    TmrTaskReport task;
    task.name = "kernel " + std::to_string(k);
    task.num_images = static_cast<int>(node.kernel_images.size());
    // The exemplar first with COLMAP's choice of a second image (most
    // matches, wide enough baseline), then with ours.
    std::vector<std::pair<int, int>> pairs = {
        {tree_.image_ids[node.exemplar], -1}};
    for (const int second : node.second_images) {
      pairs.emplace_back(tree_.image_ids[node.exemplar],
                         tree_.image_ids[second]);
    }
    std::string error;
    const auto result = work_.RunOrReuse(
        work_.KernelModel(k), o_.database_path, Ids(tree_, node.kernel_images),
        [&](const std::string& db) {
          return RunReconstructionTask(TaskOptions(num_threads), db, "", pairs,
                                       work_.KernelModel(k));
        },
        &task.reused, &error);
    if (!result) {
      task.message = error;
    } else {
      task.num_registered = result->num_registered;
      task.seconds = result->seconds;
      task.success = result->success;
      task.message = result->message;
      kernel_ok_[k] = result->success;
      base_registered_[k] = result->num_registered;
      AdoptPartModels(*result, &task);
    }
    Record(task, task.num_images);
  }

  // The models a task made of the images its main model left; they join
  // the scene models by the shared-track merge rule.
  void AdoptPartModels(const ReconstructionTaskResult& result,
                       TmrTaskReport* task) {
    if (result.part_models.empty()) return;
    task->message += "; the rest in " +
                     std::to_string(result.part_models.size()) +
                     " more models of " +
                     std::to_string(result.num_registered_in_parts) + " images";
    std::lock_guard<std::mutex> lock(mutex_);
    for (const std::string& path : result.part_models) {
      auto part = std::make_shared<colmap::Reconstruction>();
      part->ReadBinary(path);
      for (const colmap::image_t id : part->RegImageIds())
        part_images_.insert(id);
      part_models_.push_back(part);
    }
  }

  void RunLeaf(int k, int l, int num_threads) {
    const TmrKernelNode& node = tree_.kernels[k];
    TmrTaskReport task;
    task.name = "leaf " + std::to_string(k) + "." + std::to_string(l);
    task.num_images = static_cast<int>(node.leaf_clusters[l].size());
    if (!kernel_ok_[k]) {
      task.message = "its kernel task failed";
      Record(task, task.num_images);
      return;
    }
    // The kernel images, except those a part model of the kernel holds
    // (no image in two models), and the leaf's: the leaf task may also
    // register kernel images its kernel task left.
    std::vector<uint32_t> images;
    {
      std::lock_guard<std::mutex> lock(mutex_);
      for (const uint32_t id : Ids(tree_, node.kernel_images))
        if (!part_images_.count(id)) images.push_back(id);
    }
    task.num_images += static_cast<int>(images.size()) - base_registered_[k];
    for (const uint32_t id : Ids(tree_, node.leaf_clusters[l]))
      images.push_back(id);
    std::string error;
    const auto result = work_.RunOrReuse(
        work_.LeafModel(k, l), o_.database_path, images,
        [&](const std::string& db) {
          auto mapper = TaskOptions(num_threads);
          mapper.fix_existing_images = o_.fix_base_in_leaves;
          return RunReconstructionTask(mapper, db, work_.KernelModel(k), {},
                                       work_.LeafModel(k, l));
        },
        &task.reused, &error);
    if (!result) {
      task.message = error;
    } else {
      task.num_registered = result->num_registered - base_registered_[k];
      task.seconds = result->seconds;
      task.success = result->success;
      task.message = result->message;
      AdoptPartModels(*result, &task);
    }
    if (task.success) {
      std::lock_guard<std::mutex> lock(mutex_);
      finished_leaves_.emplace_back(k, l);
    }
    Record(task, task.num_images);
  }

  // Merges the leaf models of kernel k into its image-cluster model.
  void MergeCluster(int k, int num_threads) {
    if (!kernel_ok_[k] || !cache_) return;
    const auto start = Clock::now();
    std::vector<int> leaves;
    {
      std::lock_guard<std::mutex> lock(mutex_);
      for (const auto& [kernel, l] : finished_leaves_)
        if (kernel == k) leaves.push_back(l);
    }
    std::sort(leaves.begin(), leaves.end());
    std::vector<std::string> leaf_models;
    for (const int l : leaves) leaf_models.push_back(work_.LeafModel(k, l));
    const ClusterMerge merge = MergeLeafModels(
        work_.KernelModel(k), leaf_models, cache_,
        ColmapOptions(o_.mapper, num_threads), o_.merge_min_shared_tracks,
        o_.refine_merged_models);
    for (const auto& [i, reason] : merge.left_out) {
      Progress("leaf " + std::to_string(k) + "." + std::to_string(leaves[i]) +
               " left out of its cluster: " + reason);
    }
    Record({"merge cluster " + std::to_string(k),
            static_cast<int>(tree_.kernels[k].cluster_images.size()),
            static_cast<int>(merge.model->NumRegImages()), SecondsSince(start),
            true,
            std::to_string(merge.num_merged) + " leaf models" +
                (merge.track_fit.empty() ? "" : " (" + merge.track_fit + ")") +
                (merge.adjustment.empty() ? "" : "; " + merge.adjustment)});
    clusters_[k] = merge.model;
  }

  bool WriteModels(
      const std::vector<std::shared_ptr<colmap::Reconstruction>>& scenes,
      std::string* error) {
    for (size_t i = 0; i < scenes.size(); ++i) {
      if (!o_.image_path.empty())
        scenes[i]->ExtractColorsForAllImages(o_.image_path);
      const std::string path =
          (fs::path(o_.output_path) / std::to_string(i)).string();
      if (!WriteModelAtomically(*scenes[i], path)) {
        return Fail("cannot write model '" + path + "'", error);
      }
      report_->model_sizes.push_back(
          static_cast<int>(scenes[i]->NumRegImages()));
    }
    Progress("wrote " + std::to_string(scenes.size()) + " models to " +
             o_.output_path);
    return true;
  }

  const TmrMapperOptions& o_;
  TmrMapperReport* report_;
  std::function<void(const std::string&)> progress_;
  int threads_ = 1;
  TaskWorkspace work_;  // task databases and models, reused by a rerun
  TmrTree tree_;
  // Written by the tasks of the graph (each entry by one task only).
  std::vector<char> kernel_ok_;
  std::vector<int> base_registered_;  // images registered by each kernel task
  std::vector<std::shared_ptr<colmap::Reconstruction>> clusters_;
  // Models of the images a task's main model left out; under mutex_.
  std::vector<std::shared_ptr<colmap::Reconstruction>> part_models_;
  // Their images (under mutex_); a kernel's are left out of its leaf tasks.
  std::unordered_set<uint32_t> part_images_;
  std::shared_ptr<const colmap::DatabaseCache> cache_;
  // (kernel, leaf) of every leaf task that produced a model; under mutex_.
  std::vector<std::pair<int, int>> finished_leaves_;
  std::mutex mutex_;
  Clock::time_point graph_start_;
  double total_weight_ = 0.0, done_weight_ = 0.0;
};

}  // namespace

bool RunTmrMapper(const TmrMapperOptions& options, TmrMapperReport* report,
                  std::string* error,
                  const std::function<void(const std::string&)>& progress) {
  if (!options.Check(error)) return false;
  if (!options.image_path.empty() && !fs::is_directory(options.image_path)) {
    *error = "image_path '" + options.image_path + "' is not a folder";
    return false;
  }
  std::error_code ec;
  fs::create_directories(options.output_path, ec);
  if (ec) {
    *error = "cannot create output_path '" + options.output_path +
             "': " + ec.message();
    return false;
  }
  TmrMapperOptions effective = options;
  effective.match_graph.min_num_matches = options.mapper.min_num_matches;
  *report = TmrMapperReport();
  TmrMapperRun run(effective, report, progress);
  return run.Run(error);
}

}  // namespace tmr
