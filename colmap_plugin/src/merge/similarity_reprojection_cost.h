// Copyright (c) 2026, the tmr authors. BSD-3-Clause.
// A Ceres cost of the alignment by registered images
// (registration_alignment.cc).
#pragma once

#include <ceres/ceres.h>
#include <colmap/geometry/rigid3.h>

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace tmr {

// Reprojection residual of a target point moved into the source by the
// similarity (quaternion, translation, log of the scale), in a source image
// whose pose is held; in pixels at the camera's mean focal length, on the
// undistorted normalized keypoint.
struct SimilarityReprojectionCost {
  SimilarityReprojectionCost(const Eigen::Vector3d& target_xyz,
                             const Eigen::Vector2d& normalized,
                             const colmap::Rigid3d& cam_from_world,
                             double focal)
      : target_xyz_(target_xyz),
        normalized_(normalized),
        cam_from_world_(cam_from_world),
        focal_(focal) {}

  template <typename T>
  bool operator()(const T* quaternion, const T* translation, const T* log_scale,
                  T* residuals) const {
    const Eigen::Map<const Eigen::Quaternion<T>> rotation(quaternion);
    const Eigen::Map<const Eigen::Matrix<T, 3, 1>> shift(translation);
    const Eigen::Matrix<T, 3, 1> in_source =
        ceres::exp(log_scale[0]) * (rotation * target_xyz_.cast<T>()) + shift;
    const Eigen::Matrix<T, 3, 1> in_camera =
        cam_from_world_.rotation().cast<T>() * in_source +
        cam_from_world_.translation().cast<T>();
    residuals[0] =
        T(focal_) * (in_camera[0] / in_camera[2] - T(normalized_[0]));
    residuals[1] =
        T(focal_) * (in_camera[1] / in_camera[2] - T(normalized_[1]));
    return true;
  }

 private:
  Eigen::Vector3d target_xyz_;
  Eigen::Vector2d normalized_;
  colmap::Rigid3d cam_from_world_;
  double focal_;
};

}  // namespace tmr
