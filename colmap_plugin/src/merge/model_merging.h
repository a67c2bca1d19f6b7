// Copyright (c) 2026, the tmr authors. BSD-3-Clause.
#pragma once

#include <colmap/controllers/incremental_pipeline.h>
#include <colmap/geometry/sim3.h>
#include <colmap/scene/correspondence_graph.h>
#include <colmap/scene/database_cache.h>
#include <colmap/scene/reconstruction.h>

#include <memory>
#include <string>

#include "sfm/model_edits.h"

namespace tmr {

struct ModelAlignmentOptions {
  // tau of the paper: the chosen image must share more tracks than this.
  int min_shared_tracks = 12;
  // RANSAC inlier threshold on 3D points, as a share of the median distance
  // between the shared points and the target cameras that see them.
  double max_relative_error = 0.05;
  // At least this share of the anchor image's shared tracks must fit the
  // transform in 3D.
  double min_inlier_ratio = 0.5;
  // Verification on the other images' shared tracks: more than
  // min_shared_tracks of them, and at least min_relative_support times the
  // anchor image's rate, must reproject within max_reprojection_error_px.
  double min_relative_support = 0.5;
  double max_reprojection_error_px = 8.0;
  unsigned seed = 0;
};

struct ModelAlignment {
  bool success = false;
  colmap::Sim3d target_from_source;
  colmap::image_t anchor_image = colmap::kInvalidImageId;  // source image used
  int num_shared_tracks = 0;
  int num_inliers = 0;
  int num_verified = 0;  // shared tracks of other images that fit
  // AlignModelsByRegisteredImages: source images registered on the
  // target's points, and those whose observations fit the similarity.
  int num_registered_images = 0;
  int num_supporting_images = 0;
  // Of the registered images, those both models held already (a halo).
  int num_shared_images = 0;
  std::string reason;  // why the models stay apart
};

// The paper's merge rule (Sec. 5): find the image of the source model with
// the most tracks reconstructed in the target (through the correspondence
// graph); if it has more than tau such tracks, estimate the similarity
// transform from the 3D-3D pairs of those tracks with Umeyama's method
// inside COLMAP's LO-RANSAC; otherwise keep the models apart. The models may
// share no image (image clusters are disjoint), which COLMAP's own
// image-based alignment needs. When the anchor image's tracks agree, the
// similarity is estimated again from the shared tracks of all images (the
// anchor's cover a small patch, and a fit to a patch tilts away from it),
// then verified by reprojection, as COLMAP verifies its alignments: the
// other images' shared tracks must fit at half the anchor image's rate or
// better, since a wrong merge (repetitive structure, a false pair) fits the
// anchor image alone. With tau or fewer fitting tracks outside the anchor
// image the models stay apart: a wrong merge is worse than two models.
ModelAlignment AlignModelsBySharedTracks(
    const colmap::Reconstruction& target, const colmap::Reconstruction& source,
    const colmap::CorrespondenceGraph& graph,
    const ModelAlignmentOptions& options);

// How many tracks of the source images that `target` does not register are
// reconstructed in `target` (through the correspondence graph), and how
// many of those reproject onto their target observation within
// max_reprojection_error_px once moved by target_from_source: the check of
// AlignModelsBySharedTracks, for a similarity found another way.
struct SharedTrackFit {
  int num_shared = 0;
  int num_fit = 0;
};
SharedTrackFit FitSharedTracks(const colmap::Reconstruction& target,
                               const colmap::Reconstruction& source,
                               const colmap::CorrespondenceGraph& graph,
                               const colmap::Sim3d& target_from_source,
                               double max_reprojection_error_px);

// Adds the registered images of `source` that `target` does not hold,
// transformed by target_from_source, with their 3D points (observations in
// already held images are left to RefineMergedModel to re-link).
void AppendReconstruction(const colmap::Reconstruction& source,
                          const colmap::Sim3d& target_from_source,
                          colmap::Reconstruction* target);

// How RefineMergedModel bundle-adjusts a merged model.
struct MergedModelAdjustment {
  // Global bundle adjustment at all (false: tracks re-linked and points
  // filtered only).
  bool enabled = true;
  // A model of more registered images is adjusted in two smaller problems
  // (AdjustByBlocks); 0: every model whole.
  size_t max_block_images = 1000;
  // > 0: every pose adjusted on only this many longest tracks per image
  // (AdjustOnLongestTracks), at any size: enough for the large-scale shape
  // that later merges are tested against, at a part of the cost. 0: the
  // full adjustment above.
  size_t longest_tracks_per_image = 0;
  // Not empty: only these images, their cameras and their points are
  // adjusted (AdjustBlock; every other pose held where it observes those
  // points): a small part appended to a model that was adjusted before,
  // as COLMAP's local adjustment after a registration. Overrides the above.
  std::vector<colmap::image_t> only_images;
  // Rounds of adjustment, each followed by completing and merging tracks
  // and filtering points, until fewer than max_refinement_change of the
  // observations changed (COLMAP's IterativeGlobalRefinement, which ends
  // every run of its mapper with Mapper.ba_global_max_refinements = 5 and
  // 0.0005). A single adjustment of a freshly merged model stops on a
  // re-linked track set built from its unadjusted poses (figures:
  // docs/mapper.md, step 7). Only a model adjusted whole gets more than one
  // round (not by blocks, longest tracks or only_images).
  int max_refinements = 1;
  double max_refinement_change = 0.0005;
  // With rounds as above: when the last round's track merging and
  // filtering changed anything, the model is adjusted once more (then
  // filtered, not re-linked), so that the model written was adjusted after
  // its last change. COLMAP's refinement stops with that change
  // unadjusted, which left a merged scene three times less accurate
  // (docs/mapper.md, step 7).
  bool adjust_after_last_change = false;
  // > 0: the full adjustment (not by blocks, longest tracks or
  // only_images) runs as blocks of at most this many images
  // (CovisibleImageBlocks) adjusted side by side, num_workers at once
  // (AdjustBlocksAtOnce): for a model whose large-scale shape an
  // adjustment on its longest tracks has just fixed.
  size_t parallel_block_images = 0;
  int num_workers = 1;
};

// What RefineMergedModel did: each round's adjustment and the points
// filtered, and the time of every block adjusted side by side.
struct MergedModelRefinement {
  std::string report;
  std::vector<double> block_seconds;
  // Wall time of those adjustments at once, writing back included.
  double blocks_wall_seconds = 0;
};

// Global bundle adjustment of the mapper's model with COLMAP's residuals,
// loss and gauge (IncrementalMapper::AdjustGlobalBundle), but a direct
// sparse Schur solver at every size and Ceres' convergence test
// (AdjustWholeModel). COLMAP switches to an iterative solver above
// 1,000 images and runs its global adjustments to the iteration limit,
// which on merged models took ten times as long for twice the error. A
// model of more than adjustment.max_block_images is adjusted in two
// smaller problems (AdjustByBlocks: every pose on the longest tracks, then
// blocks of at most that many images), since memory is the problem's, not
// the solver's (figures: docs/mapper.md, step 7); with
// adjustment.parallel_block_images, blocks side by side
// (AdjustBlocksAtOnce), their times added to `refinement`. Returns the
// solver's name and Ceres' one-line report, empty when there was nothing
// to adjust.
std::string AdjustMergedBundle(
    const colmap::IncrementalPipelineOptions& mapper_options,
    const MergedModelAdjustment& adjustment, colmap::IncrementalMapper* mapper,
    MergedModelRefinement* refinement = nullptr);

// Re-links tracks across the merged parts (complete and merge tracks over
// the full correspondence graph, retriangulation), then global bundle
// adjustment (AdjustMergedBundle), track merging and point filtering, in
// adjustment.max_refinements rounds at most, as COLMAP's mapper refines a
// grown model (IterativeGlobalRefinement).
MergedModelRefinement RefineMergedModel(
    const std::shared_ptr<const colmap::DatabaseCache>& database_cache,
    const colmap::IncrementalPipelineOptions& mapper_options,
    const MergedModelAdjustment& adjustment,
    const std::shared_ptr<colmap::Reconstruction>& model);

}  // namespace tmr
