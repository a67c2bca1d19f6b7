// Copyright (c) 2026, the tmr authors. BSD-3-Clause.
// The bundle adjustments of a merged model: re-linked tracks, then rounds
// of adjustment, track merging and filtering, as COLMAP's mapper refines a
// grown model.
#pragma once

#include <colmap/controllers/incremental_pipeline.h>
#include <colmap/scene/database_cache.h>
#include <colmap/scene/reconstruction.h>
#include <colmap/sfm/incremental_mapper.h>

#include <memory>
#include <string>
#include <vector>

namespace tmr {

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
