// Copyright (c) 2026, the tmr authors. BSD-3-Clause.
#include "merge/scene_assembly.h"

#include <algorithm>
#include <chrono>
#include <unordered_set>

#include "merge/merged_model_refinement.h"
#include "merge/model_alignment.h"
#include "sfm/model_edits.h"
#include "tmr/util/process.h"

namespace tmr {
namespace {

using Clock = std::chrono::steady_clock;

// Each scene remembers its registered images (AssemblyScene::held).
void HoldImages(std::vector<AssemblyScene>* scenes) {
  for (AssemblyScene& scene : *scenes) {
    const std::vector<colmap::image_t>& ids = scene.model->RegImageIds();
    scene.held = {ids.begin(), ids.end()};
  }
}

std::vector<std::shared_ptr<colmap::Reconstruction>> ModelsLargestFirst(
    std::vector<AssemblyScene>* scenes) {
  SortBySize(scenes);
  std::vector<std::shared_ptr<colmap::Reconstruction>> models;
  for (const AssemblyScene& scene : *scenes) models.push_back(scene.model);
  return models;
}

}  // namespace

std::string DescribeFit(const ModelAlignment& a) {
  if (a.num_registered_images > 0) {
    return std::to_string(a.num_supporting_images) + " of " +
           std::to_string(a.num_registered_images) +
           " images registered on the scene's points fit" +
           (a.num_shared_images > 0
                ? " (" + std::to_string(a.num_shared_images) +
                      " in both models)"
                : "");
  }
  return std::to_string(a.num_inliers) + " of " +
         std::to_string(a.num_shared_tracks) + " shared tracks fit";
}

void SortBySize(std::vector<AssemblyScene>* scenes) {
  std::sort(scenes->begin(), scenes->end(),
            [](const AssemblyScene& a, const AssemblyScene& b) {
              return a.model->NumRegImages() > b.model->NumRegImages();
            });
}

SceneAssembler::SceneAssembler(
    SceneAssemblyOptions options,
    std::shared_ptr<const colmap::DatabaseCache> cache,
    std::string merge_database, std::vector<std::string> image_names,
    std::function<void(const TmrTaskReport&)> record)
    : o_(std::move(options)),
      cache_(std::move(cache)),
      merge_database_(std::move(merge_database)),
      image_names_(std::move(image_names)),
      record_(std::move(record)) {
  for (const auto& [pair_id, num_correspondences] :
       cache_->CorrespondenceGraph()->NumMatchesBetweenAllImages()) {
    if (num_correspondences == 0) continue;
    const auto [id1, id2] = colmap::PairIdToImagePair(pair_id);
    image_links_[id1].emplace_back(id2, num_correspondences);
    image_links_[id2].emplace_back(id1, num_correspondences);
  }
}

std::vector<std::shared_ptr<colmap::Reconstruction>> SceneAssembler::Assemble(
    const std::vector<std::shared_ptr<colmap::Reconstruction>>& models,
    bool drop_small_models) const {
  Scenes scenes;
  for (const auto& model : models)
    scenes.push_back({model, false, model->NumRegImages(), {}});
  // Links the averaging refused get their second try against the refined
  // scenes, below.
  if (o_.align_all_at_once) AlignAllScenes(&scenes);
  // Every later step takes each image to be in one model: the halo images
  // that no merge above joined keep the copy with the most points.
  std::vector<colmap::Reconstruction*> models_now;
  for (AssemblyScene& scene : scenes) models_now.push_back(scene.model.get());
  KeepOneCopyOfEachImage(models_now);
  if (!o_.align_all_at_once) MergeScenes(&scenes);
  if (o_.complete_models) {
    CompleteScenes(&scenes);
    // New models from what is left may overlap the others.
    if (ReconstructLeftovers(&scenes)) MergeScenes(&scenes);
  }
  RefineMergedScenes(&scenes);
  // A model whose shared tracks disagreed with a scene of unrefined merges
  // (loops not yet closed) gets a second try against the refined scene
  // (docs/mapper.md, step 8).
  if (scenes.size() > 1) {
    HoldImages(&scenes);
    const size_t before = scenes.size();
    MergeScenes(&scenes);
    if (scenes.size() < before) RefineLateMerges(&scenes);
  }
  // A last completion on the refined scenes, whose retriangulation made
  // points that photos left out before can register on (tmr_synth plazas of
  // 960: 4 photos of a plaza whose neighbours joined by the last merges;
  // `colmap image_registrator` registered them on the final model).
  if (o_.complete_models) {
    HoldImages(&scenes);
    CompleteScenes(&scenes, /*keep_unless_grown=*/true);
    RefineLateMerges(&scenes);
  }
  if (drop_small_models) DropSmallModels(&scenes);
  return ModelsLargestFirst(&scenes);
}

void SceneAssembler::DropSmallModels(Scenes* scenes) const {
  // As COLMAP's mapper: with several models, those below min_model_size
  // images (at most 80% of all) are dropped; their photos stay unregistered.
  const size_t min_size = MinModelSize();
  SortBySize(scenes);
  int dropped = 0, images = 0;
  while (scenes->size() > 1 &&
         scenes->back().model->NumRegImages() < min_size) {
    ++dropped;
    images += static_cast<int>(scenes->back().model->NumRegImages());
    scenes->pop_back();  // largest first
  }
  RecordDroppedModels(dropped, images);
}

void SceneAssembler::RecordDroppedModels(int num_dropped,
                                         int num_images) const {
  if (num_dropped == 0) return;
  record_({"drop " + std::to_string(num_dropped) + " models of fewer than " +
               std::to_string(MinModelSize()) +
               " images (Mapper.min_model_size)",
           num_images, 0, 0.0, true, "their images stay unregistered"});
}

size_t SceneAssembler::MinModelSize() const {
  return std::min<size_t>(static_cast<size_t>(0.8 * image_names_.size()),
                          static_cast<size_t>(o_.mapper.min_model_size));
}

void SceneAssembler::MergeScenes(Scenes* scenes) const {
  SortBySize(scenes);
  // Each model joins the first scene it aligns with, the most strongly
  // linked first; repeat until nothing merges, since a merge can create
  // new overlaps.
  bool merged = true;
  while (merged) {
    merged = false;
    Scenes next;
    for (AssemblyScene& candidate : *scenes) {
      const colmap::Reconstruction& model = *candidate.model;
      bool joined = false;
      // A model below the smallest that COLMAP keeps is too weak to move
      // as one block (docs/mapper.md, step 4: three photos with wrong focal
      // lengths ended far away). Where models are completed, its photos are
      // registered one by one instead (CompleteScenes).
      const bool too_small =
          o_.complete_models && model.NumRegImages() < MinModelSize();
      for (const int s :
           too_small ? std::vector<int>() : LinkedScenes(model, next)) {
        AssemblyScene& scene = next[s];
        const auto start = Clock::now();
        const ModelAlignment a = Align(*scene.model, model);
        TmrTaskReport task{"merge a model of " +
                               std::to_string(model.NumRegImages()) +
                               " images into a scene of " +
                               std::to_string(scene.model->NumRegImages()),
                           static_cast<int>(model.NumRegImages()),
                           0,
                           0.0,
                           a.success,
                           a.success ? DescribeFit(a) : a.reason};
        if (a.success) {
          AppendReconstruction(model, a.target_from_source, scene.model.get());
          scene.unrefined = true;
          task.num_registered = static_cast<int>(scene.model->NumRegImages());
        }
        task.seconds = SecondsSince(start);
        record_(task);
        if (a.success) {
          if (scene.model->NumRegImages() >=
              o_.refinement_growth * scene.refined_size)
            Refine(&scene, /*while_merging=*/true);
          joined = merged = true;
          break;
        }
      }
      if (!joined) next.push_back(std::move(candidate));
    }
    *scenes = std::move(next);
    SortBySize(scenes);
  }
}

void SceneAssembler::RefineMergedScenes(Scenes* scenes) const {
  for (AssemblyScene& scene : *scenes) {
    if (scene.unrefined) Refine(&scene, /*while_merging=*/false);
  }
}

void SceneAssembler::RefineLateMerges(Scenes* scenes) const {
  for (AssemblyScene& scene : *scenes) {
    if (!scene.unrefined) continue;
    std::vector<colmap::image_t> joined;
    for (const colmap::image_t id : scene.model->RegImageIds())
      if (!scene.held.count(id)) joined.push_back(id);
    if (scene.model->NumRegImages() >=
        kFullAdjustmentGrowth * scene.held.size())
      joined.clear();  // a full adjustment
    Refine(&scene, /*while_merging=*/false, joined);
  }
}

void SceneAssembler::Refine(
    AssemblyScene* scene, bool while_merging,
    const std::vector<colmap::image_t>& only_images) const {
  const auto start = Clock::now();
  MergedModelAdjustment adjustment =
      while_merging ? o_.growing_adjustment : o_.merged_adjustment;
  adjustment.only_images = only_images;
  adjustment.adjust_after_last_change = !while_merging && only_images.empty();
  // A scene merged at once was adjusted on its longest tracks first
  // (AlignAllScenes).
  if (!while_merging && o_.align_all_at_once) {
    adjustment.parallel_block_images = o_.parallel_block_images;
    adjustment.num_workers = o_.num_threads;
  }
  const MergedModelRefinement refinement =
      RefineMergedModel(cache_, o_.mapper, adjustment, scene->model);
  ReleaseFreedMemory();
  const int images = static_cast<int>(scene->model->NumRegImages());
  const bool full =
      adjustment.longest_tracks_per_image == 0 && only_images.empty();
  TmrTaskReport row{
      full                  ? "refine merged model"
      : only_images.empty() ? "refine growing scene"
                            : "refine late merge",
      images,
      images,
      SecondsSince(start),
      true,
      "tracks merged, global bundle adjustment: " + refinement.report};
  row.part_seconds = refinement.block_seconds;
  row.parts_wall_s = refinement.blocks_wall_seconds;
  record_(row);
  if (full) scene->unrefined = false;
  scene->refined_size = scene->model->NumRegImages();
}

}  // namespace tmr
