// Copyright (c) 2026, the tmr authors. BSD-3-Clause.
#pragma once

#include <colmap/controllers/incremental_pipeline.h>
#include <colmap/geometry/sim3.h>
#include <colmap/scene/database_cache.h>
#include <colmap/scene/reconstruction.h>

#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <unordered_map>
#include <unordered_set>
#include <vector>

#include "merge/merged_model_refinement.h"
#include "merge/shared_track_alignment.h"
#include "merge/similarity_averaging.h"
#include "sfm/model_edits.h"
#include "tmr/colmap/task_report.h"

namespace tmr {

// What SceneAssembler takes of tmr_mapper's options, already turned into
// COLMAP's where COLMAP runs (filled by AssemblyOptions,
// controllers/tmr_mapper_options.h).
struct SceneAssemblyOptions {
  // COLMAP's mapper options for completion, leftovers and refinement: also
  // the smallest model kept (min_model_size) and the inliers that
  // registering an image needs (mapper.abs_pose_min_num_inliers).
  colmap::IncrementalPipelineOptions mapper;
  // The adjustment of a scene while it grows (on its longest tracks), and
  // that of a merged scene.
  MergedModelAdjustment growing_adjustment;
  MergedModelAdjustment merged_adjustment;
  // The alignment rules: shared tracks needed (tau), images registered on
  // the other model's points (0: that rule off), their RANSAC's seed.
  int min_shared_tracks = 0;
  int register_images = 0;
  unsigned seed = 0;
  // Every linked pair aligned at once (AlignAllScenes) or scene by scene
  // (MergeScenes); completion of the scenes with the images no model
  // holds; a growing scene's size between two of its adjustments, as a
  // share of its last adjusted size; a merged scene's blocks adjusted side
  // by side (0: none).
  bool align_all_at_once = false;
  bool complete_models = false;
  double refinement_growth = 0;
  size_t parallel_block_images = 0;
  // Workers: linked pairs aligned at once, blocks adjusted side by side.
  int num_threads = 1;
};

// Takes out of `scene` the images registered since `before` that see fewer
// than `min_anchored` points also seen by an image of `before`: an image
// placed mostly on points that other new images triangulated moves with
// them, and a group of such images can settle far off (docs/mapper.md,
// step 5). Returns how many it took out; they stay in `scene`,
// unregistered.
int RemoveUnanchoredImages(const std::unordered_set<colmap::image_t>& before,
                           int min_anchored, colmap::Reconstruction* scene);

// Two linked models of an assembly or a join, aligned
// (SceneAssembler::AlignModelPairs): how strongly verified pairs link them,
// how the alignment went, and, when it held, the link it gives the
// similarity averaging (model2's points on the seam).
struct ModelPairAlignment {
  int model1 = 0;  // model1 < model2
  int model2 = 0;
  int num_pairs = 0;  // verified image pairs between them
  int num_correspondences = 0;
  ModelAlignment alignment;  // model1_from_model2 when it succeeded
  double seconds = 0;
  std::optional<SimilarityLink> link;
};

// The models placed by one similarity averaging of the links of their
// aligned pairs, and each averaged link's index in those pairs.
struct PlacedModels {
  SimilarityAveraging averaging;
  std::vector<size_t> link_pair;  // each averaged link's index in pairs
};
PlacedModels PlaceModelPairs(int num_models,
                             const std::vector<ModelPairAlignment>& pairs);

// The report rows of an alignment of models at once (`model_sizes` by
// model number): the step's (its pairs, links held, the scenes it made and
// the second copies of images it took out), then one per aligned pair,
// held by the averaging or why not, with the pair's models in `link`. The
// alignments ran in parallel inside the step, so their rows take no time
// of their own in the assembly's chain of steps.
std::vector<TmrTaskReport> AlignmentRows(
    const std::vector<size_t>& model_sizes,
    const std::vector<ModelPairAlignment>& pairs, const PlacedModels& placed,
    size_t num_scenes, int num_copies, double seconds);

// What a join (SceneAssembler::PlaceJoin) knows of one of its models
// without holding it: its registered images, and the number of 3D points
// of each of those images that another model may hold too (the seams),
// which decides the copy kept (DroppedImageCopies).
struct JoinModel {
  size_t num_images = 0;
  std::unordered_map<colmap::image_t, size_t> seam_image_points;
};

// One model of a join as a part of a joined scene: its index among the
// joined models, the similarity that places it in the scene, and its
// images whose copy in another model was kept instead.
struct JoinPiece {
  int model = 0;
  colmap::Sim3d scene_from_model;
  std::vector<colmap::image_t> dropped_images;
};

// A scene of a join: how to make it from the whole models, piece after
// piece in order, and its registered images.
struct JoinedScene {
  std::vector<JoinPiece> pieces;
  size_t num_images = 0;
};

// A scene model and its refinement state, carried through the passes of
// SceneAssembler::Assemble. The state lives and dies with its scene: a
// model that merges into another leaves the list with it.
struct AssemblyScene {
  std::shared_ptr<colmap::Reconstruction> model;
  // Merged or completed since its last full global adjustment.
  bool unrefined = false;
  // Registered images at its last global adjustment, or when it entered
  // the assembly.
  size_t refined_size = 0;
  // Registered images before the current late pass (RefineLateMerges).
  std::unordered_set<colmap::image_t> held;
};

// Orders scenes by registered images, largest first.
void SortBySize(std::vector<AssemblyScene>* scenes);

// What a successful alignment rested on, for the report.
std::string DescribeFit(const ModelAlignment& alignment);

// The last steps of tmr_mapper (paper Sec. 5, after the tasks of the tree):
// image-cluster models become scene models by the shared-track merge rule
// (merge/shared_track_alignment.h) or by images registered on the scene's
// points (merge/registration_alignment.h), then COLMAP's mapper completes them
// with the images no model holds, and maps from scratch what is still left
// (the image-cluster models come from merge/cluster_merge.h). How two
// models are linked and aligned (Links, LinkedScenes, Align, WeakLinks) is
// in scene_links.cc, the completion passes in scene_completion.cc.
class SceneAssembler {
 public:
  // COLMAP's mapper adjusts a model globally when it has grown by 10%
  // (Mapper.ba_global_images_ratio).
  static constexpr double kFullAdjustmentGrowth = 1.1;

  // `merge_database`: a task database of all images (COLMAP's controller
  // reads a path); `cache`: its correspondences, loaded once; `record`
  // receives every step for the report.
  SceneAssembler(SceneAssemblyOptions options,
                 std::shared_ptr<const colmap::DatabaseCache> cache,
                 std::string merge_database,
                 std::vector<std::string> image_names,
                 std::function<void(const TmrTaskReport&)> record);

  // The whole last stage: AlignAllScenes (or, without
  // options.align_all_at_once, MergeScenes), CompleteScenes,
  // ReconstructLeftovers
  // (the last two when options.complete_models), RefineMergedScenes,
  // then MergeScenes once more on the refined scenes and RefineLateMerges,
  // and (options.complete_models) CompleteScenes on the refined
  // scenes with RefineLateMerges of the images it added. Returns the scene
  // models, largest first; with `drop_small_models`, without the models
  // below MinModelSize when there are several (as COLMAP's mapper).
  std::vector<std::shared_ptr<colmap::Reconstruction>> Assemble(
      const std::vector<std::shared_ptr<colmap::Reconstruction>>& models,
      bool drop_small_models = true) const;

  // Every linked pair of `models` (verified pairs between them, or images
  // both hold) that `wanted` accepts (all when null) aligned by Align, in
  // parallel on options.num_threads, in the order of (model1, model2).
  std::vector<ModelPairAlignment> AlignModelPairs(
      const std::vector<const colmap::Reconstruction*>& models,
      bool images_first,
      const std::function<bool(int, int)>& wanted = nullptr) const;

  // The join of a merge stage by parts (docs/distributed.md), from the
  // alignments of its linked models (AlignModelPairs, run pair of groups
  // by pair of groups, each on the correspondences of its seams only, so
  // that no step holds every group's seams): one similarity averaging
  // places the models, each image keeps the copy with the most points (the
  // lower model number on a tie), each connected part becomes a scene of
  // its models in order, and the scenes below MinModelSize go when there
  // are several. `models` are numbered largest first, as AlignAllScenes
  // numbers them. Returns the scenes largest first, and in *weak_links the
  // scenes that verified pairs link but the alignments or the averaging
  // kept apart: their models' verified pairs and matches (counted before
  // second copies of images were dropped), and the alignment or the
  // refusal of their strongest model pair (WeakLinks would align the
  // scenes again, which needs them whole). Needs no correspondences.
  std::vector<JoinedScene> PlaceJoin(
      const std::vector<JoinModel>& models,
      std::vector<ModelPairAlignment> pairs,
      std::vector<TmrWeakLink>* weak_links) const;

  // Every pair of `scenes` (the final models, in output order) that
  // verified pairs link: how strongly, and why Align keeps them apart.
  std::vector<TmrWeakLink> WeakLinks(
      const std::vector<std::shared_ptr<colmap::Reconstruction>>& scenes) const;

 private:
  using Scenes = std::vector<AssemblyScene>;

  // Each model joins the first scene it aligns with (Align), the scenes
  // tried in order of the verified matches between them and the model,
  // those without any skipped, until nothing merges; leaves the scenes
  // largest first. With options.complete_models, a model below
  // MinModelSize stays apart: CompleteScenes registers its photos one by
  // one. A scene is refined (Refine) whenever it has grown by
  // options.refinement_growth since its last global adjustment, as COLMAP's
  // mapper refines a model grown by 10%: parts appended one after another
  // around a city's loops drift apart, later parts then fit only in
  // places, and one adjustment at the end starts too far off
  // (docs/mapper.md, step 4). Between those, merges add no adjustment: one
  // per merge would cost far more.
  void MergeScenes(Scenes* scenes) const;
  // MergeScenes' first pass with options.align_all_at_once: every
  // pair of linked models (those of at least MinModelSize images where
  // models are completed) aligned by Align, in parallel; one similarity
  // averaging of those alignments (AverageSimilarities); each connected
  // part appended into its largest model in the averaged frame, left to
  // RefineMergedScenes for its one adjustment (scene_averaging.cc),
  // adjusted first on its longest tracks.
  void AlignAllScenes(Scenes* scenes) const;
  // With several scenes, those below MinModelSize go, largest first; their
  // images stay unregistered.
  void DropSmallModels(Scenes* scenes) const;
  // DropSmallModels' report row, when it dropped any.
  void RecordDroppedModels(int num_dropped, int num_images) const;
  // Mapper.min_model_size, at most 80% of the images (as COLMAP's mapper).
  size_t MinModelSize() const;

  // COLMAP's incremental mapper continues each scene, largest first, with
  // the images no larger scene holds (registration and local refinement on
  // the loaded correspondences; the scene is then left to
  // RefineMergedScenes): those no model holds, and the second chance of
  // the images of smaller models that no merge joined to it (a leaf's part
  // model mapped from scratch because its photos see points of another
  // kernel's cluster). An image registered so leaves its smaller model;
  // models left with fewer than two images are dropped. With
  // `keep_unless_grown`, a scene that gains no image is left exactly as it
  // was: the attempts alone move a refined scene slightly (which of
  // COLMAP's steps does is not traced). Those moves are repeatable; the
  // run-to-run differences first blamed on them came from the unseeded
  // generator of the cluster merge's alignment (MergeLeafModels).
  void CompleteScenes(Scenes* scenes, bool keep_unless_grown = false) const;

  // Refines the scenes merged or completed since their last global
  // adjustment: tracks completed and merged over the full correspondence
  // graph, global bundle adjustment, point filtering.
  void RefineMergedScenes(Scenes* scenes) const;

  // After the second try of the models that did not fit before
  // RefineMergedScenes, or the last completion (each scene's `held`: its
  // images before): a scene that this grew by less than
  // kFullAdjustmentGrowth gets an adjustment of only the images that
  // joined, with their points (MergedModelAdjustment::only_images), a
  // larger one a full one again: a second full adjustment costs as much as
  // the first, and the lighter one of the refinements while merging moves
  // every pose (docs/mapper.md, step 8).
  void RefineLateMerges(Scenes* scenes) const;

  // Maps the images no scene holds from scratch (several models if need
  // be) and adds the models; returns whether it added any.
  bool ReconstructLeftovers(Scenes* scenes) const;

  // Re-links tracks, global adjustment and filtering (RefineMergedModel):
  // the full adjustment, or while merging the one that the options ask for
  // then (MergedAdjustment), or of `only_images` when not empty.
  void Refine(AssemblyScene* scene, bool while_merging,
              const std::vector<colmap::image_t>& only_images = {}) const;

  // The scene merge of `model` into `scene`: the shared-track rule
  // (AlignModelsBySharedTracks), and where it refuses, images of the model
  // registered on the scene's points (AlignModelsByRegisteredImages, with
  // options.register_images). On refusal the reason names both.
  // With `images_first`, the images' rule is tried first: it aligns on the
  // poses of the images both models hold, which fix the rotation better
  // than the tracks of a seam.
  ModelAlignment Align(const colmap::Reconstruction& scene,
                       const colmap::Reconstruction& model,
                       bool images_first = false) const;

  // Indices of the scenes that verified pairs link `model` to, the one with
  // the most verified matches first.
  std::vector<int> LinkedScenes(const colmap::Reconstruction& model,
                                const Scenes& scenes) const;

  // Verified image pairs between `model` and each of `scenes`, and their
  // matches.
  struct ModelLink {
    int num_pairs = 0;
    int num_correspondences = 0;
  };
  std::vector<ModelLink> Links(
      const colmap::Reconstruction& model,
      const std::vector<const colmap::Reconstruction*>& scenes) const;

  const SceneAssemblyOptions o_;
  std::shared_ptr<const colmap::DatabaseCache> cache_;
  std::string merge_database_;
  std::vector<std::string> image_names_;
  std::function<void(const TmrTaskReport&)> record_;
  // Verified pairs of each image: partner and number of correspondences.
  std::unordered_map<colmap::image_t,
                     std::vector<std::pair<colmap::image_t, int>>>
      image_links_;
};

}  // namespace tmr
