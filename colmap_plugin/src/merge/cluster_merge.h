// Copyright (c) 2026, the tmr authors. BSD-3-Clause.
#pragma once

#include <colmap/controllers/incremental_pipeline.h>
#include <colmap/scene/database_cache.h>
#include <colmap/scene/reconstruction.h>

#include <memory>
#include <string>
#include <vector>

#include "merge/merged_model_refinement.h"
#include "merge/shared_track_alignment.h"

namespace tmr {

// The image-cluster model of a kernel (paper Sec. 5.2): its kernel model
// with each leaf model appended, then refined once. A kernel model that no
// leaf joined stays as COLMAP's mapper left it, after its final global
// refinement.
struct ClusterMerge {
  struct LeftOut {
    int leaf;            // index into the leaf models
    std::string reason;  // why it was not appended
  };
  std::shared_ptr<colmap::Reconstruction> model;
  int num_merged = 0;             // leaf models appended
  std::vector<LeftOut> left_out;  // leaf models not appended
  std::string track_fit;   // per appended leaf: shared tracks that reproject
  std::string adjustment;  // summary of the refinement, if any
};

// Each leaf model extends a copy of the kernel model, but the mapper
// normalises every model after global adjustment, so a leaf model has its
// own frame: it is aligned on the kernel images both share with COLMAP's
// reprojection-verified alignment and appended. The alignment is then
// checked on the leaf's own images as scene merges are
// (FitSharedTracks): at least half of their tracks that the cluster model
// reconstructs must reproject, since a leaf that a mapper placed badly
// still aligns on the kernel images it holds fixed. A leaf that fails
// either test is left out; its images go to completion.
ClusterMerge MergeLeafModels(const std::string& kernel_model,
                             const std::vector<std::string>& leaf_models,
                             std::shared_ptr<const colmap::DatabaseCache> cache,
                             const colmap::IncrementalPipelineOptions& mapper,
                             int min_shared_tracks,
                             const MergedModelAdjustment& adjustment);

}  // namespace tmr
