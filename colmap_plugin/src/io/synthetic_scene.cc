// Copyright (c) 2026, the tmr authors. BSD-3-Clause.
#include "tmr/colmap/synthetic_scene.h"

#include <colmap/math/random.h>
#include <colmap/scene/database.h>
#include <colmap/scene/reconstruction.h>
#include <colmap/scene/synthetic.h>

#include <filesystem>

namespace tmr {

bool SyntheticSceneOptions::Check(std::string* error) const {
  auto fail = [&](const std::string& message) {
    if (error) *error = message;
    return false;
  };
  if (num_images < 2) return fail("num_images must be >= 2");
  if (num_cameras < 1 || num_cameras > num_images) {
    return fail("num_cameras must be in [1, num_images]");
  }
  if (num_points3D < 1) return fail("num_points3D must be >= 1");
  if (num_unmatched_keypoints < 0) {
    return fail("num_unmatched_keypoints must be >= 0");
  }
  if (keypoint_noise_px < 0) return fail("keypoint_noise_px must be >= 0");
  return true;
}

bool WriteSyntheticScene(const SyntheticSceneOptions& options,
                         const std::string& database_path,
                         const std::string& model_path, std::string* error) {
  namespace fs = std::filesystem;
  if (!options.Check(error)) return false;
  if (fs::exists(database_path)) {
    *error = "database '" + database_path + "' already exists";
    return false;
  }
  const fs::path parent = fs::path(database_path).parent_path();
  std::error_code ec;
  if (!parent.empty()) fs::create_directories(parent, ec);
  if (ec) {
    *error = "cannot create folder '" + parent.string() + "': " + ec.message();
    return false;
  }
  colmap::SyntheticDatasetOptions synthetic;
  synthetic.num_images = options.num_images;
  synthetic.num_cameras = options.num_cameras;
  synthetic.num_points3D = options.num_points3D;
  synthetic.num_points2D_without_point3D = options.num_unmatched_keypoints;
  synthetic.point2D_stddev = options.keypoint_noise_px;
  colmap::SetPRNGSeed(options.seed);
  colmap::Reconstruction reconstruction;
  {
    colmap::Database database(database_path);
    colmap::SynthesizeDataset(synthetic, &reconstruction, &database);
  }
  if (!model_path.empty()) {
    fs::create_directories(model_path, ec);
    if (ec) {
      *error = "cannot create folder '" + model_path + "': " + ec.message();
      return false;
    }
    reconstruction.WriteBinary(model_path);
  }
  return true;
}

}  // namespace tmr
