// Copyright (c) 2026, the tmr authors. BSD-3-Clause.
#pragma once

#include <cstdint>
#include <string>

namespace tmr {

// A synthetic scene written as a COLMAP database plus its ground-truth model.
// For now a thin wrapper over COLMAP's SynthesizeDataset (cameras on a
// sphere around random points, exhaustive matches between observations).
struct SyntheticSceneOptions {
  // Number of images.
  int num_images = 30;
  // Number of cameras (intrinsics) shared by the images.
  int num_cameras = 1;
  // Number of 3D points.
  int num_points3D = 1500;
  // Keypoints per image that match nothing.
  int num_unmatched_keypoints = 200;
  // Pixel noise of the keypoints (standard deviation).
  double keypoint_noise_px = 0.5;
  // Seed of COLMAP's random generator.
  uint32_t seed = 0;

  bool Check(std::string* error = nullptr) const;
};

// Writes `database_path` (must not exist yet) through COLMAP's Database class
// and the ground truth in COLMAP binary format into `model_path` (created if
// missing; empty string: no model). Returns false with a reason in `error`
// on failure.
bool WriteSyntheticScene(const SyntheticSceneOptions& options,
                         const std::string& database_path,
                         const std::string& model_path, std::string* error);

}  // namespace tmr
