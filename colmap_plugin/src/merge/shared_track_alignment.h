// Copyright (c) 2026, the tmr authors. BSD-3-Clause.
// The paper's merge rule: the similarity between two models from the tracks
// they share (Sec. 5).
#pragma once

#include <colmap/geometry/sim3.h>
#include <colmap/scene/correspondence_graph.h>
#include <colmap/scene/reconstruction.h>

#include "merge/model_alignment.h"

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

}  // namespace tmr
