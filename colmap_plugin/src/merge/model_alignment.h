// Copyright (c) 2026, the tmr authors. BSD-3-Clause.
// The result of aligning one model to another, by shared tracks
// (merge/shared_track_alignment.h) or by images registered on the other's
// points (merge/registration_alignment.h).
#pragma once

#include <colmap/geometry/sim3.h>
#include <colmap/util/types.h>

#include <string>

namespace tmr {

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

}  // namespace tmr
