// Copyright (c) 2026, the tmr authors. BSD-3-Clause.
//
// Source images of one model posed in another model's frame, for
// AlignModelsByRegisteredImages: registered on the target's points, or held
// by both models already (a halo).
#pragma once

#include <colmap/scene/correspondence_graph.h>
#include <colmap/scene/reconstruction.h>

#include <utility>
#include <vector>

#include "merge/registration_alignment.h"

namespace tmr {

// An image of the source with a pose in the target's frame, and its
// keypoints on the target's points (the registration's inliers).
struct RegisteredImage {
  colmap::image_t image_id;
  colmap::Rigid3d target_cam_from_world;
  std::vector<std::pair<colmap::point2D_t, colmap::point3D_t>> inliers;
};

struct RegistrationOnTarget {
  std::vector<RegisteredImage> images;
  int num_shared = 0;  // of `images`, those both models held
  int num_tried = 0;   // registrations tried
  // The source image with the most correspondences to the target's points
  // (none held by the target), and their number.
  colmap::image_t anchor_image = colmap::kInvalidImageId;
  int anchor_correspondences = 0;
};

// Up to options.max_images source images posed in the target: first those
// both models register (SharedImages: the target's pose, no registration),
// then those with the most 2D-3D correspondences to the target's points
// (through the correspondence graph), each registered on them as COLMAP
// registers an image (P3P in LO-RANSAC, then pose refinement, the source's
// intrinsics held); at most 3 max_images registrations are tried.
RegistrationOnTarget RegisterSourceImagesOnTarget(
    const colmap::Reconstruction& target, const colmap::Reconstruction& source,
    const colmap::CorrespondenceGraph& graph,
    const RegistrationAlignmentOptions& options);

}  // namespace tmr
