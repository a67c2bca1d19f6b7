// Copyright (c) 2026, the tmr authors. BSD-3-Clause.
#include "merge/cluster_merge.h"

#include <colmap/estimators/alignment.h>
#include <colmap/math/random.h>

#include "sfm/model_edits.h"

namespace tmr {

ClusterMerge MergeLeafModels(const std::string& kernel_model,
                             const std::vector<std::string>& leaf_models,
                             std::shared_ptr<const colmap::DatabaseCache> cache,
                             const colmap::IncrementalPipelineOptions& mapper,
                             int min_shared_tracks,
                             const MergedModelAdjustment& adjustment) {
  // COLMAP's thresholds for its own reprojection-verified alignment
  // (MergeReconstructions); the shared tracks are held to the same 8 px.
  constexpr double kMaxReprojErrorPx = 8.0;
  constexpr double kMinFitShare = 0.5;
  ClusterMerge merge;
  merge.model = std::make_shared<colmap::Reconstruction>();
  merge.model->ReadBinary(kernel_model);
  for (int l = 0; l < static_cast<int>(leaf_models.size()); ++l) {
    colmap::Reconstruction leaf;
    leaf.ReadBinary(leaf_models[l]);
    colmap::Sim3d model_from_leaf;
    // COLMAP's alignment takes no seed: its RANSAC draws from the thread's
    // generator, whose state depends on the tasks this worker ran before
    // (two workers against one gave another cluster model).
    if (mapper.random_seed >= 0) colmap::SetPRNGSeed(mapper.random_seed);
    if (!colmap::AlignReconstructionsViaReprojections(
            leaf, *merge.model,
            /*min_inlier_observations=*/0.3, kMaxReprojErrorPx,
            &model_from_leaf)) {
      merge.left_out.push_back(
          {l, "fewer than 30% of the kernel images' observations reproject"});
      continue;
    }
    const SharedTrackFit fit =
        FitSharedTracks(*merge.model, leaf, *cache->CorrespondenceGraph(),
                        model_from_leaf, kMaxReprojErrorPx);
    const std::string fit_text = std::to_string(fit.num_fit) + " of " +
                                 std::to_string(fit.num_shared) +
                                 " shared tracks reproject";
    if (fit.num_shared > min_shared_tracks &&
        fit.num_fit < kMinFitShare * fit.num_shared) {
      merge.left_out.push_back({l, fit_text});
      continue;
    }
    AppendReconstruction(leaf, model_from_leaf, merge.model.get());
    ++merge.num_merged;
    merge.track_fit += (merge.track_fit.empty() ? "" : ", ") + fit_text;
  }
  if (merge.num_merged > 0) {
    merge.adjustment =
        RefineMergedModel(std::move(cache), mapper, adjustment, merge.model)
            .report;
  }
  return merge;
}

}  // namespace tmr
