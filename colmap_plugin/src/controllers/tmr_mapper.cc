// Copyright (c) 2026, the tmr authors. BSD-3-Clause.
#include "tmr/colmap/tmr_mapper.h"

#include <colmap/scene/database_cache.h>
#include <glog/logging.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <mutex>
#include <numeric>
#include <sstream>
#include <thread>
#include <unordered_set>

#include "controllers/memory_budget.h"
#include "controllers/task_graph.h"
#include "controllers/tmr_mapper_report.h"
#include "controllers/tmr_mapper_run.h"
#include "controllers/tmr_mapper_stages.h"
#include "tmr/io/atomic_file.h"
#include "tmr/util/process.h"

namespace tmr {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

// The in-process run: the stages of TmrMapperStages on one task graph,
// with progress lines and an ETA.
class TmrMapperRun {
 public:
  TmrMapperRun(const TmrMapperOptions& options, TmrMapperReport* report,
               const std::function<void(const std::string&)>& progress)
      : o_(options),
        report_(report),
        progress_(progress),
        stages_(options),
        threads_(TmrMapperThreads(options)) {}

  bool Run(std::string* error) {
    start_ = Clock::now();
    if (!stages_.Plan(
            report_, /*one_process=*/true,
            [this](const std::string& l) { Progress(l); }, error))
      return false;
    if (!RunTaskGraph(error)) return false;
    const auto record = [this](const TmrTaskReport& t) { Record(t); };
    const auto progress = [this](const std::string& l) { Progress(l); };
    if (!stages_.cluster_groups().empty()) {
      if (!stages_.JoinGroups(threads_, record, progress, report_, error))
        return false;
    } else {
      std::vector<std::shared_ptr<colmap::Reconstruction>> clusters;
      for (auto& cluster : clusters_)
        if (cluster) clusters.push_back(std::move(cluster));
      if (!stages_.AssembleAndWrite(std::move(clusters), cache_, threads_,
                                    record, progress, report_, error))
        return false;
    }
    FinishTmrMapper(o_, stages_, start_, /*timeline=*/true, progress_, report_);
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

  // Reports a step that has just finished: node `node` of the task graph,
  // or (-1) a step of the scene assembly after it. `weight` (images) drives
  // the ETA of the task graph.
  void Record(TmrTaskReport task, int node = -1, double weight = 0.0) {
    std::lock_guard<std::mutex> lock(mutex_);
    task.start_s = std::max(0.0, SecondsSince(start_) - task.seconds);
    task.in_task_graph = node >= 0;
    const ProcessMemory memory = ReadProcessMemory();
    task.rss_mib = memory.rss_mib;
    task.peak_mib = memory.peak_mib;
    const int row = static_cast<int>(report_->tasks.size());
    if (node >= 0 && row_of_node_[node] >= 0) {
      task.depends = {row_of_node_[node]};  // a node's steps form a chain
      row_of_node_[node] = row;
    } else if (node >= 0) {
      for (const int d : node_depends_[node])
        if (row_of_node_[d] >= 0) task.depends.push_back(row_of_node_[d]);
      row_of_node_[node] = row;
    } else if (row > 0 && !report_->tasks.back().in_task_graph) {
      task.depends = {row - 1};  // the assembly's steps form one chain
    } else {
      for (int r = 0; r < row; ++r) task.depends.push_back(r);
    }
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
  // tenth per image. By parts, a group's merge (with its cluster merges)
  // waits for its clusters' tasks, and no correspondences of all images
  // are loaded.
  bool RunTaskGraph(std::string* error) {
    const TmrTree& tree = stages_.tree();
    const bool by_parts = !stages_.cluster_groups().empty();
    clusters_.assign(tree.kernels.size(), nullptr);
    TaskGraph graph;
    std::string cache_error;
    std::vector<std::vector<int>> merge_depends(tree.kernels.size());
    if (!by_parts) {
      const int cache = AddNode(
          &graph, {"load correspondences", 1e12, {}, [&](int) {
                     const auto load_start = Clock::now();
                     cache_ = stages_.LoadCache(&cache_error);
                     if (cache_) {
                       const int n = static_cast<int>(tree.image_ids.size());
                       Record({"load correspondences", n, n,
                               SecondsSince(load_start), true, ""},
                              /*node=*/0);  // the first node
                     }
                   }});
      for (auto& depends : merge_depends) depends.push_back(cache);
    }
    std::vector<int> kernel_node(tree.kernels.size(), -1);
    total_weight_ = done_weight_ = 0.0;
    std::mutex error_mutex;
    std::string task_error;
    auto fail = [&](const std::string& message) {
      std::lock_guard<std::mutex> lock(error_mutex);
      if (task_error.empty()) task_error = message;
    };
    for (const TmrMapperTask& task : stages_.Tasks()) {
      const double weight = task.num_images;
      total_weight_ += weight;
      const int node = graph.NumTasks();
      auto run = [this, task, weight, node, fail](int threads) {
        TmrTaskReport row;
        std::string e;
        if (!stages_.RunTask(task, threads, &row, &e))
          return fail(task.id + ": " + e);
        Record(row, node, weight);
      };
      const bool kernel = task.leaf < 0;
      const int id = AddNode(
          &graph, {kernel ? "kernel" : "leaf",
                   kernel ? weight : weight + 0.3 * task.num_base_images,
                   kernel ? std::vector<int>{}
                          : std::vector<int>{kernel_node[task.kernel]},
                   run, task.memory_mib});
      if (kernel) kernel_node[task.kernel] = id;
      merge_depends[task.kernel].push_back(id);
    }
    const auto progress = [this](const std::string& l) { Progress(l); };
    const auto& groups = stages_.cluster_groups();
    for (int g = 0; g < static_cast<int>(groups.size()); ++g) {
      std::vector<int> depends;
      for (const int k : groups[g].kernels)
        depends.insert(depends.end(), merge_depends[k].begin(),
                       merge_depends[k].end());
      const int node = graph.NumTasks();
      AddNode(&graph, {"merge group", 0.1 * groups[g].num_images, depends,
                       [this, g, node, progress, fail](int threads) {
                         std::string e;
                         if (!stages_.MergeGroup(
                                 g, threads,
                                 [this, node](const TmrTaskReport& row) {
                                   Record(row, node);
                                 },
                                 progress, &e))
                           fail("merge group " + std::to_string(g) + ": " + e);
                       },
                       groups[g].memory_mib});
    }
    for (int k = 0; !by_parts && k < static_cast<int>(tree.kernels.size());
         ++k) {
      const int node = graph.NumTasks();
      AddNode(&graph,
              stages_.ClusterMergeTask(
                  k, merge_depends[k], &cache_, progress,
                  [this, node](const TmrTaskReport& row) { Record(row, node); },
                  &clusters_[k]));
    }
    graph_start_ = Clock::now();
    // Without parts, the correspondences of all images stay loaded beside
    // the tasks.
    graph.Run(
        threads_,
        std::max(1.0,
                 stages_.budget().mib -
                     (by_parts ? 0.0 : stages_.CorrespondencesMemoryMiB())));
    if (!by_parts && !cache_) return Fail(cache_error, error);
    if (!task_error.empty()) return Fail(task_error, error);
    return true;
  }

  // Adds a task to the graph and remembers its dependencies for the
  // report's rows.
  int AddNode(TaskGraph* graph, TaskGraph::Task task) {
    node_depends_.push_back(task.depends);
    row_of_node_.push_back(-1);
    return graph->Add(std::move(task));
  }

  const TmrMapperOptions& o_;
  TmrMapperReport* report_;
  std::function<void(const std::string&)> progress_;
  TmrMapperStages stages_;
  int threads_ = 1;
  // Written by the merge tasks of the graph (each entry by one task only).
  std::vector<std::shared_ptr<colmap::Reconstruction>> clusters_;
  std::shared_ptr<const colmap::DatabaseCache> cache_;
  std::mutex mutex_;
  // The task graph's dependencies, and the report row of each node that
  // has finished (-1 before).
  std::vector<std::vector<int>> node_depends_;
  std::vector<int> row_of_node_;
  Clock::time_point start_, graph_start_;
  double total_weight_ = 0.0, done_weight_ = 0.0;
};

}  // namespace

bool RunTmrMapper(const TmrMapperOptions& options, TmrMapperReport* report,
                  std::string* error,
                  const std::function<void(const std::string&)>& progress) {
  TmrMapperOptions effective;
  if (!PrepareTmrMapper(options, &effective, error)) return false;
  *report = TmrMapperReport();
  TmrMapperRun run(effective, report, progress);
  return run.Run(error);
}

void ConfigureColmapLogging(const char* program, bool verbose) {
  FLAGS_logtostderr = true;
  FLAGS_minloglevel = verbose ? google::GLOG_INFO : google::GLOG_WARNING;
  if (!google::IsGoogleLoggingInitialized()) google::InitGoogleLogging(program);
}

}  // namespace tmr
