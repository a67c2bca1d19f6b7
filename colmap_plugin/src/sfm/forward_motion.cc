// Copyright (c) 2026, the tmr authors. BSD-3-Clause.
#include "sfm/forward_motion.h"

#include <colmap/scene/two_view_geometry.h>

#include <Eigen/SVD>
#include <unordered_map>

namespace tmr {
namespace {

// The unit vector spanning the left null space of a rank-2 matrix.
Eigen::Vector3d LeftNullVector(const Eigen::Matrix3d& m) {
  const Eigen::JacobiSVD<Eigen::Matrix3d> svd(m, Eigen::ComputeFullU);
  return svd.matrixU().col(2);
}

}  // namespace

ForwardMotionStats MeasureForwardMotion(const colmap::Database& database,
                                        double max_forward_motion) {
  ForwardMotionStats stats;
  std::unordered_map<colmap::camera_t, colmap::Camera> cameras;
  for (colmap::Camera& camera : database.ReadAllCameras()) {
    ++stats.num_cameras;
    if (camera.has_prior_focal_length) ++stats.num_cameras_with_prior_focal;
    cameras.emplace(camera.camera_id, std::move(camera));
  }
  std::unordered_map<colmap::image_t, colmap::camera_t> camera_of;
  for (const colmap::Image& image : database.ReadAllImages())
    camera_of[image.ImageId()] = image.CameraId();

  using Config = colmap::TwoViewGeometry::ConfigurationType;
  for (const auto& [pair_id, geometry] : database.ReadTwoViewGeometries()) {
    Eigen::Vector3d t;
    if (geometry.config == Config::CALIBRATED && geometry.E) {
      t = LeftNullVector(*geometry.E);
    } else if (geometry.config == Config::UNCALIBRATED && geometry.F) {
      const auto image2 =
          camera_of.find(colmap::PairIdToImagePair(pair_id).second);
      if (image2 == camera_of.end()) continue;
      const auto camera2 = cameras.find(image2->second);
      if (camera2 == cameras.end()) continue;
      const colmap::Camera& c = camera2->second;
      // The epipole in image 2 is K2 t.
      const Eigen::Vector3d e2 = LeftNullVector(*geometry.F);
      t = Eigen::Vector3d(e2.x() - c.PrincipalPointX() * e2.z(),
                          e2.y() - c.PrincipalPointY() * e2.z(),
                          c.MeanFocalLength() * e2.z());
    } else {
      continue;  // planar, panoramic, degenerate: no translation direction
    }
    if (!t.allFinite() || t.norm() == 0.0) continue;
    ++stats.num_pairs;
    if (std::abs(t.z()) > max_forward_motion * t.norm()) ++stats.num_forward;
  }
  return stats;
}

}  // namespace tmr
