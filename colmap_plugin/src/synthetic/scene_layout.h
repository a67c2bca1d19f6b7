// Copyright (c) 2026, the tmr authors. BSD-3-Clause.
// Geometry of synthetic scenes: textured boxes and camera poses (Eigen only).
#pragma once

#include <Eigen/Core>
#include <random>
#include <string>
#include <vector>

#include "tmr/colmap/synthetic_scene.h"

namespace tmr {
namespace synthetic {

// A box standing on the ground (z = 0), rotated by `yaw` about the z axis.
// Its vertical faces carry texture (3D points) where `textured_faces` has the
// bit of the face: 1 = +x, 2 = -x, 4 = +y, 8 = -y (local axes).
struct Box {
  Eigen::Vector2d center = Eigen::Vector2d::Zero();
  double yaw = 0.0;
  Eigen::Vector3d half_size = Eigen::Vector3d::Ones();
  int textured_faces = 15;

  // True if the open segment from `from` to `to` passes through the box.
  bool Blocks(const Eigen::Vector3d& from, const Eigen::Vector3d& to) const;
};

struct ScenePoint {
  Eigen::Vector3d xyz;
  Eigen::Vector3d normal;
  int box;
};

struct SceneCamera {
  Eigen::Vector3d center;
  Eigen::Matrix3d cam_from_world;  // rows: right, down, viewing direction
  std::string part;                // name prefix, e.g. "place0", "street"
};

struct SceneLayout {
  std::vector<Box> boxes;
  std::vector<SceneCamera> cameras;
};

// Boxes and cameras of the family named in options.family.
SceneLayout BuildSceneLayout(const SyntheticSceneOptions& options,
                             std::mt19937_64& rng);

// Samples points uniformly on the textured faces (Poisson count with the
// given density per square metre, from 0.3 m above ground to the top), each
// displaced along the face normal by up to +-relief metres.
std::vector<ScenePoint> SampleScenePoints(const std::vector<Box>& boxes,
                                          double density, double relief,
                                          std::mt19937_64& rng);

// Rotation of a camera at horizontal heading `yaw` (radians, 0 = +x) tilted
// up by `pitch`, with the image x axis to the right and y axis down.
Eigen::Matrix3d LookRotation(double yaw, double pitch);

}  // namespace synthetic
}  // namespace tmr
