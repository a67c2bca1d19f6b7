// Copyright (c) 2026, the tmr authors. BSD-3-Clause.
// TmrMapperStages' merge stage (paper Sec. 5.2 and after): each kernel's
// cluster merge, the scene assembly of the cluster and part models, and
// the models written to output_path.
#include <algorithm>
#include <chrono>
#include <filesystem>

#include "controllers/tmr_mapper_options.h"
#include "controllers/tmr_mapper_stages.h"
#include "io/model_files.h"
#include "merge/cluster_merge.h"
#include "merge/scene_assembly.h"
#include "tmr/io/atomic_file.h"
#include "tmr/util/process.h"

namespace tmr {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

}  // namespace

std::shared_ptr<colmap::Reconstruction> TmrMapperStages::MergeCluster(
    int k, std::shared_ptr<const colmap::DatabaseCache> cache, int num_threads,
    TmrTaskReport* row, std::vector<std::string>* notes) const {
  const auto start = Clock::now();
  if (!ReadKernelState(k).success) return nullptr;
  const TmrKernelNode& node = tree_.kernels[k];
  std::vector<int> leaves;
  std::vector<std::string> leaf_models;
  for (int l = 0; l < static_cast<int>(node.leaf_clusters.size()); ++l) {
    ReconstructionTaskResult result;
    if (work_.Finished(work_.LeafModel(k, l), &result) && result.success) {
      leaves.push_back(l);
      leaf_models.push_back(work_.LeafModel(k, l));
    }
  }
  const ClusterMerge merge = MergeLeafModels(
      work_.KernelModel(k), leaf_models, std::move(cache),
      ColmapOptions(o_, num_threads), o_.merge.min_shared_tracks,
      MergedAdjustment(o_, /*while_merging=*/false));
  ReleaseFreedMemory();
  for (const auto& [i, reason] : merge.left_out) {
    notes->push_back("leaf " + std::to_string(k) + "." +
                     std::to_string(leaves[i]) +
                     " left out of its cluster: " + reason);
  }
  size_t num_images = node.cluster_images.size();  // and its halo
  for (const auto& halo : node.leaf_halos) num_images += halo.size();
  *row = {"merge cluster " + std::to_string(k),
          static_cast<int>(num_images),
          static_cast<int>(merge.model->NumRegImages()),
          SecondsSince(start),
          true,
          std::to_string(merge.num_merged) + " leaf models" +
              (merge.track_fit.empty() ? "" : " (" + merge.track_fit + ")") +
              (merge.adjustment.empty() ? "" : "; " + merge.adjustment)};
  return merge.model;
}

std::vector<std::shared_ptr<colmap::Reconstruction>>
TmrMapperStages::PartModels(const std::vector<int>* kernels) const {
  std::vector<std::shared_ptr<colmap::Reconstruction>> parts;
  for (const TmrMapperTask& task : PlannedTasks()) {
    if (kernels && std::find(kernels->begin(), kernels->end(), task.kernel) ==
                       kernels->end())
      continue;
    ReconstructionTaskResult result;
    if (!work_.Finished(Model(task), &result)) continue;
    for (const std::string& path : result.part_models) {
      parts.push_back(std::make_shared<colmap::Reconstruction>());
      parts.back()->ReadBinary(path);
    }
  }
  return parts;
}

bool TmrMapperStages::AssembleAndWrite(
    std::vector<std::shared_ptr<colmap::Reconstruction>> models,
    std::shared_ptr<const colmap::DatabaseCache> cache, int num_threads,
    const Record& record, const Progress& progress, TmrMapperReport* report,
    std::string* error) const {
  for (auto& part : PartModels()) models.push_back(std::move(part));
  const SceneAssembler assembler(AssemblyOptions(o_, num_threads),
                                 std::move(cache), work_.MergeDatabase(),
                                 tree_.image_names, record);
  const std::vector<std::shared_ptr<colmap::Reconstruction>> scenes =
      assembler.Assemble(models);
  return WriteScenes(scenes, assembler, progress, report, error);
}

bool TmrMapperStages::WriteScenes(
    const std::vector<std::shared_ptr<colmap::Reconstruction>>& scenes,
    const SceneAssembler& assembler, const Progress& progress,
    TmrMapperReport* report, std::string* error) const {
  for (size_t i = 0; i < scenes.size(); ++i) {
    if (!o_.image_path.empty())
      scenes[i]->ExtractColorsForAllImages(o_.image_path);
    const std::string path =
        (fs::path(o_.output_path) / std::to_string(i)).string();
    if (!WriteModelAtomically(*scenes[i], path))
      return Fail("cannot write model '" + path + "'", error);
    report->model_sizes.push_back(static_cast<int>(scenes[i]->NumRegImages()));
  }
  FinishScenes(scenes.size(), assembler.WeakLinks(scenes), progress, report);
  return true;
}

void TmrMapperStages::FinishScenes(size_t num_scenes,
                                   std::vector<TmrWeakLink> weak_links,
                                   const Progress& progress,
                                   TmrMapperReport* report) const {
  // Models of an earlier run into the same folder that this one has no
  // number for would read as part of its result.
  for (size_t i = num_scenes;; ++i) {
    const fs::path stale = fs::path(o_.output_path) / std::to_string(i);
    std::error_code ec;
    if (!fs::is_directory(stale, ec)) break;
    fs::remove_all(stale, ec);
  }
  report->weak_links = std::move(weak_links);
  if (progress) {
    progress("wrote " + std::to_string(num_scenes) + " models to " +
             o_.output_path);
    for (const TmrWeakLink& w : report->weak_links) {
      progress("models " + std::to_string(w.model1) + " and " +
               std::to_string(w.model2) +
               " stay apart: " + std::to_string(w.num_pairs) +
               " verified pairs (" + std::to_string(w.num_correspondences) +
               " matches); " + w.reason);
    }
  }
}

TaskGraph::Task TmrMapperStages::ClusterMergeTask(
    int k, std::vector<int> depends,
    const std::shared_ptr<const colmap::DatabaseCache>* cache,
    const Progress& progress, const Record& record,
    std::shared_ptr<colmap::Reconstruction>* cluster) const {
  return {"merge", 0.1 * tree_.kernels[k].cluster_images.size(),
          std::move(depends),
          [=](int threads) {
            if (!*cache) return;
            TmrTaskReport row;
            std::vector<std::string> notes;
            *cluster = MergeCluster(k, *cache, threads, &row, &notes);
            for (const std::string& note : notes) progress(note);
            if (*cluster) record(row);
          },
          ClusterMergeMemoryMiB(k)};
}

std::vector<std::shared_ptr<colmap::Reconstruction>>
TmrMapperStages::MergeClusters(
    const std::vector<int>& kernels,
    std::shared_ptr<const colmap::DatabaseCache> cache, int num_threads,
    const Record& record, const Progress& progress) const {
  std::vector<std::shared_ptr<colmap::Reconstruction>> clusters(kernels.size());
  TaskGraph graph;
  for (size_t i = 0; i < kernels.size(); ++i)
    graph.Add(ClusterMergeTask(kernels[i], {}, &cache, progress, record,
                               &clusters[i]));
  graph.Run(num_threads);
  clusters.erase(std::remove(clusters.begin(), clusters.end(), nullptr),
                 clusters.end());
  return clusters;
}

}  // namespace tmr
