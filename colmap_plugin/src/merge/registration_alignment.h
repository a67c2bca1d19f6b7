// Copyright (c) 2026, the tmr authors. BSD-3-Clause.
#pragma once

#include <colmap/scene/correspondence_graph.h>
#include <colmap/scene/reconstruction.h>

#include "merge/shared_track_alignment.h"

namespace tmr {

struct RegistrationAlignmentOptions {
  // Source images tried, those with the most 2D-3D correspondences to the
  // target's points first; the search stops after this many registered.
  int max_images = 10;
  // An image counts as registered in the target with at least this many
  // inliers of this share of its correspondences
  // (Mapper.abs_pose_min_num_inliers, abs_pose_min_inlier_ratio).
  int min_num_inliers = 30;
  double min_inlier_ratio = 0.25;
  // RANSAC threshold of the absolute pose (Mapper.abs_pose_max_error).
  double max_abs_pose_error_px = 12.0;
  // An image supports the similarity when at least this share of the
  // source points it observes, moved into the target, reproject onto their
  // keypoints within max_reprojection_error_px in its pose there (COLMAP's
  // MergeReconstructions: 0.3 and 8 px).
  double min_inlier_observations = 0.3;
  double max_reprojection_error_px = 8.0;
  // At least this many registered images, and half of them, must support it.
  int min_images = 3;
  // The supporting images' centres must spread by at least this share of
  // the depth of what they see (RMS distance from their mean over the median
  // depth): images taken from one spot leave the scale undetermined.
  double min_center_spread = 0.02;
  unsigned seed = 0;
};

// Scene merge by shared images (the overlap of COLMAP's hierarchical mapper,
// made after the fact): the images both models register (the halo of
// neighbouring clusters, tmr/partition/cluster_halo.h) hold a pose in each
// already; up to max_images with those, the source images that see the most
// points of the target are registered on those points by absolute pose
// (COLMAP's P3P LO-RANSAC and pose refinement, the source's intrinsics held),
// so each holds a pose in both models. Every pair of them proposes the
// similarity that carries their source poses onto their target poses (rotations
// averaged, scale and translation from the projection centres); the one
// that most images support, estimated again from those, is kept. An image
// supports it when the source points it observes, moved into the target,
// reproject onto their keypoints in its target pose: the models need to
// share no track, only points seen from the same photos. It holds where
// clusters share many points but few tracks for AlignModelsBySharedTracks
// (short tracks seen from far away give noisy 3D-3D pairs; a pose from
// hundreds of 2D-3D matches is well determined). Two parts linked by one photo
// pair, or by false pairs (random matches that no pose explains), register
// fewer than min_images images and stay apart. Neither model is changed.
ModelAlignment AlignModelsByRegisteredImages(
    const colmap::Reconstruction& target, const colmap::Reconstruction& source,
    const colmap::CorrespondenceGraph& graph,
    const RegistrationAlignmentOptions& options);

}  // namespace tmr
