// Copyright (c) 2026, the tmr authors. BSD-3-Clause.
#include "merge/merged_model_refinement.h"

#include <colmap/estimators/bundle_adjustment.h>

#include <string>

#include "sfm/block_adjustment.h"
#include "sfm/parallel_block_adjustment.h"

namespace tmr {

std::string AdjustMergedBundle(
    const colmap::IncrementalPipelineOptions& mapper_options,
    const MergedModelAdjustment& adjustment, colmap::IncrementalMapper* mapper,
    MergedModelRefinement* refinement) {
  colmap::Reconstruction& model = *mapper->Reconstruction();
  const size_t num_images = model.NumRegImages();
  if (num_images < 2) return "";
  mapper->ObservationManager().FilterObservationsWithNegativeDepth();
  const colmap::BundleAdjustmentOptions options =
      mapper_options.GlobalBundleAdjustment();
  if (!adjustment.only_images.empty()) {
    const BlockAdjustment block =
        AdjustBlock(adjustment.only_images, options, &model);
    return "block of " + std::to_string(adjustment.only_images.size()) +
           " images, " + std::to_string(block.num_iterations) + " iterations" +
           (block.converged ? "" : ", not converged");
  }
  if (adjustment.longest_tracks_per_image > 0) {
    return AdjustOnLongestTracks(options, adjustment.longest_tracks_per_image,
                                 &model);
  }
  if (adjustment.max_block_images > 0 &&
      num_images > adjustment.max_block_images)
    return AdjustByBlocks(options, adjustment.max_block_images, &model);
  if (adjustment.parallel_block_images > 0 &&
      num_images > adjustment.parallel_block_images) {
    const BlocksAdjustment blocks = AdjustBlocksAtOnce(
        CovisibleImageBlocks(model, adjustment.parallel_block_images), options,
        adjustment.num_workers, &model);
    if (refinement != nullptr) {
      refinement->block_seconds.insert(refinement->block_seconds.end(),
                                       blocks.block_seconds.begin(),
                                       blocks.block_seconds.end());
      refinement->blocks_wall_seconds += blocks.seconds;
    }
    return blocks.Describe();
  }
  return AdjustWholeModel(options, &model);
}

MergedModelRefinement RefineMergedModel(
    const std::shared_ptr<const colmap::DatabaseCache>& database_cache,
    const colmap::IncrementalPipelineOptions& mapper_options,
    const MergedModelAdjustment& adjustment,
    const std::shared_ptr<colmap::Reconstruction>& model) {
  colmap::IncrementalMapper mapper(database_cache);
  mapper.BeginReconstruction(model);
  const auto triangulation = mapper_options.Triangulation();
  mapper.CompleteAndMergeTracks(triangulation);
  mapper.Retriangulate(triangulation);
  MergedModelRefinement refinement;
  std::string& report = refinement.report;
  size_t filtered = 0;
  // A model adjusted by blocks gets one round: repeated block passes made
  // it three times less accurate (docs/mapper.md, step 7).
  const bool by_blocks = adjustment.max_block_images > 0 &&
                         model->NumRegImages() > adjustment.max_block_images;
  const int rounds = adjustment.enabled && !by_blocks &&
                             adjustment.only_images.empty() &&
                             adjustment.longest_tracks_per_image == 0
                         ? adjustment.max_refinements
                         : 1;
  size_t changed = 0;
  for (int round = 0; round < rounds; ++round) {
    const size_t num_observations = model->ComputeNumObservations();
    if (adjustment.enabled) {
      report +=
          (round > 0 ? "; round " + std::to_string(round + 1) + ": " : "") +
          AdjustMergedBundle(mapper_options, adjustment, &mapper, &refinement);
    }
    changed = mapper.CompleteAndMergeTracks(triangulation);
    const size_t round_filtered = mapper.FilterPoints(mapper_options.Mapper());
    filtered += round_filtered;
    changed += round_filtered;
    if (num_observations == 0 ||
        changed < adjustment.max_refinement_change * num_observations)
      break;
  }
  if (adjustment.enabled && adjustment.adjust_after_last_change && rounds > 1 &&
      changed > 0) {
    report +=
        "; after " + std::to_string(changed) + " changed observations: " +
        AdjustMergedBundle(mapper_options, adjustment, &mapper, &refinement);
    filtered += mapper.FilterPoints(mapper_options.Mapper());
  }
  mapper.EndReconstruction(/*discard=*/false);
  report += (report.empty() ? "" : "; ") + std::to_string(filtered) +
            " points filtered";
  return refinement;
}

}  // namespace tmr
