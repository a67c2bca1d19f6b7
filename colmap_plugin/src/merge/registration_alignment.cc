// Copyright (c) 2026, the tmr authors. BSD-3-Clause.
#include "merge/registration_alignment.h"

#include <ceres/ceres.h>
#include <colmap/scene/projection.h>

#include <algorithm>
#include <cmath>

#include "merge/similarity_reprojection_cost.h"
#include "merge/target_registration.h"

namespace tmr {
namespace {

// Reprojection error (px) of the target point `point3D_id`, moved into the
// source by source_from_target, at keypoint `idx` of the source image of
// `r` in its source pose.
double SourceReprojectionError(const colmap::Reconstruction& target,
                               const colmap::Reconstruction& source,
                               const RegisteredImage& r, colmap::point2D_t idx,
                               colmap::point3D_t point3D_id,
                               const colmap::Sim3d& source_from_target) {
  const colmap::Image& image = source.Image(r.image_id);
  return std::sqrt(colmap::CalculateSquaredReprojectionError(
      image.Point2D(idx).xy,
      source_from_target * target.Point3D(point3D_id).xyz,
      image.CamFromWorld().ToMatrix(), source.Camera(image.CameraId())));
}

// Share of the registration inliers of `r` that reproject within max_px
// (SourceReprojectionError).
double FittingShare(const colmap::Reconstruction& target,
                    const colmap::Reconstruction& source,
                    const RegisteredImage& r,
                    const colmap::Sim3d& source_from_target, double max_px) {
  int fit = 0;
  for (const auto& [idx, point3D_id] : r.inliers) {
    fit += SourceReprojectionError(target, source, r, idx, point3D_id,
                                   source_from_target) <= max_px;
  }
  return r.inliers.empty() ? 0.0 : static_cast<double>(fit) / r.inliers.size();
}

// The similarity that best carries the target points of the registration
// inliers onto their keypoints in the source images' own poses (which the
// source's bundle adjustment fixed, unlike the registered poses, which can
// trade rotation for translation when an image sees a narrow band of
// depths), from `source_from_target` on, with the correspondences within
// max_px of it and a robust loss. False when too few are left.
bool RefineOnObservations(const colmap::Reconstruction& target,
                          const colmap::Reconstruction& source,
                          const std::vector<RegisteredImage>& registered,
                          double max_px, colmap::Sim3d* source_from_target) {
  Eigen::Quaterniond rotation = source_from_target->rotation();
  Eigen::Vector3d translation = source_from_target->translation();
  double log_scale = std::log(source_from_target->scale());
  ceres::Problem problem;
  int num_residuals = 0;
  for (const RegisteredImage& r : registered) {
    const colmap::Image& image = source.Image(r.image_id);
    const colmap::Camera& camera = source.Camera(image.CameraId());
    for (const auto& [idx, point3D_id] : r.inliers) {
      const std::optional<Eigen::Vector2d> normalized =
          camera.CamFromImg(image.Point2D(idx).xy);
      if (!normalized ||
          SourceReprojectionError(target, source, r, idx, point3D_id,
                                  *source_from_target) > max_px)
        continue;
      problem.AddResidualBlock(
          new ceres::AutoDiffCostFunction<SimilarityReprojectionCost, 2, 4, 3,
                                          1>(new SimilarityReprojectionCost(
              target.Point3D(point3D_id).xyz, *normalized, image.CamFromWorld(),
              camera.MeanFocalLength())),
          new ceres::HuberLoss(1.0), rotation.coeffs().data(),
          translation.data(), &log_scale);
      ++num_residuals;
    }
  }
  if (num_residuals < 6) return false;
  problem.SetManifold(rotation.coeffs().data(),
                      new ceres::EigenQuaternionManifold);
  ceres::Solver::Options options;
  options.linear_solver_type = ceres::DENSE_QR;
  options.max_num_iterations = 50;
  options.num_threads = 1;
  ceres::Solver::Summary summary;
  ceres::Solve(options, &problem, &summary);
  if (!summary.IsSolutionUsable()) return false;
  *source_from_target =
      colmap::Sim3d(std::exp(log_scale), rotation.normalized(), translation);
  return true;
}

// The similarity that carries the source poses of `images` onto their
// target poses: the rotation averaged over the images (R = R_t^T R_s for
// each), scale and translation by least squares on the projection centres.
// False when the centres do not spread.
bool SimilarityFromPoses(const colmap::Reconstruction& source,
                         const std::vector<const RegisteredImage*>& images,
                         colmap::Sim3d* target_from_source) {
  Eigen::Vector4d sum = Eigen::Vector4d::Zero();
  Eigen::Vector3d mean_source = Eigen::Vector3d::Zero();
  Eigen::Vector3d mean_target = Eigen::Vector3d::Zero();
  std::vector<Eigen::Vector3d> source_centers, target_centers;
  for (const RegisteredImage* r : images) {
    const colmap::Image& image = source.Image(r->image_id);
    const Eigen::Quaterniond q = r->target_cam_from_world.rotation().inverse() *
                                 image.CamFromWorld().rotation();
    const Eigen::Vector4d v = q.coeffs();
    sum += (sum.dot(v) < 0 ? -1.0 : 1.0) * v;
    source_centers.push_back(image.ProjectionCenter());
    target_centers.push_back(
        colmap::Inverse(r->target_cam_from_world).translation());
    mean_source += source_centers.back() / images.size();
    mean_target += target_centers.back() / images.size();
  }
  const Eigen::Quaterniond rotation =
      Eigen::Quaterniond(sum(3), sum(0), sum(1), sum(2)).normalized();
  double numerator = 0, denominator = 0;
  for (size_t i = 0; i < images.size(); ++i) {
    const Eigen::Vector3d ds = rotation * (source_centers[i] - mean_source);
    numerator += (target_centers[i] - mean_target).dot(ds);
    denominator += ds.squaredNorm();
  }
  if (denominator <= 0 || numerator <= 0) return false;
  const double scale = numerator / denominator;
  *target_from_source = colmap::Sim3d(
      scale, rotation, mean_target - scale * (rotation * mean_source));
  return true;
}

// Images among `registered` whose registration inliers fit
// source_from_target (FittingShare), and the number of inliers that fit.
std::vector<const RegisteredImage*> Supporting(
    const colmap::Reconstruction& target, const colmap::Reconstruction& source,
    const std::vector<RegisteredImage>& registered,
    const colmap::Sim3d& source_from_target, double max_px,
    const RegistrationAlignmentOptions& options, int* num_fit) {
  std::vector<const RegisteredImage*> inliers;
  *num_fit = 0;
  for (const RegisteredImage& r : registered) {
    const double share =
        FittingShare(target, source, r, source_from_target, max_px);
    *num_fit += static_cast<int>(std::lround(share * r.inliers.size()));
    if (share >= options.min_inlier_observations) inliers.push_back(&r);
  }
  return inliers;
}

// Root mean square distance of the images' source projection centres from
// their mean, over the median depth of the source points they observe:
// below a few percent (one spot turning round), the scale is unknown.
double CenterSpread(const colmap::Reconstruction& source,
                    const std::vector<const RegisteredImage*>& images) {
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (const RegisteredImage* r : images)
    mean += source.Image(r->image_id).ProjectionCenter() / images.size();
  double squared = 0;
  std::vector<double> depths;
  for (const RegisteredImage* r : images) {
    const colmap::Image& image = source.Image(r->image_id);
    squared += (image.ProjectionCenter() - mean).squaredNorm() / images.size();
    for (const colmap::Point2D& p : image.Points2D()) {
      if (p.HasPoint3D())
        depths.push_back(
            (image.CamFromWorld() * source.Point3D(p.point3D_id).xyz).z());
    }
  }
  if (depths.empty()) return 0;
  std::nth_element(depths.begin(), depths.begin() + depths.size() / 2,
                   depths.end());
  const double depth = depths[depths.size() / 2];
  return depth > 0 ? std::sqrt(squared) / depth : 0;
}

}  // namespace

ModelAlignment AlignModelsByRegisteredImages(
    const colmap::Reconstruction& target, const colmap::Reconstruction& source,
    const colmap::CorrespondenceGraph& graph,
    const RegistrationAlignmentOptions& options) {
  ModelAlignment result;
  RegistrationOnTarget on_target =
      RegisterSourceImagesOnTarget(target, source, graph, options);
  const std::vector<RegisteredImage>& registered = on_target.images;
  result.anchor_image = on_target.anchor_image;
  result.num_shared_tracks = on_target.anchor_correspondences;
  result.num_shared_images = on_target.num_shared;
  const int tried = on_target.num_tried;
  result.num_registered_images = static_cast<int>(registered.size());
  if (result.num_registered_images < options.min_images) {
    result.reason = (result.num_shared_images > 0
                         ? std::to_string(result.num_shared_images) +
                               " images in both models and "
                         : "") +
                    std::to_string(result.num_registered_images -
                                   result.num_shared_images) +
                    " of " + std::to_string(tried) +
                    " source images tried register on the target's points "
                    "(needs " +
                    std::to_string(options.min_images) + ")";
    return result;
  }
  // Every pair of registered images proposes a similarity from their poses
  // (few images: all pairs, no sampling). The one that the most
  // registration inliers fit, within a loose threshold since registered
  // poses can be a little off, is refined on the inliers in the source
  // poses, first those within the loose threshold, then those within
  // max_reprojection_error_px.
  const double max_px = options.max_reprojection_error_px;
  const double loose_px = 4 * max_px;
  colmap::Sim3d source_from_target;
  int best_fit = 0;
  for (size_t a = 0; a < registered.size(); ++a) {
    for (size_t b = a + 1; b < registered.size(); ++b) {
      colmap::Sim3d sim;
      if (!SimilarityFromPoses(source, {&registered[a], &registered[b]}, &sim))
        continue;
      const colmap::Sim3d inverse = colmap::Inverse(sim);
      int fit = 0;
      Supporting(target, source, registered, inverse, loose_px, options, &fit);
      if (fit > best_fit) {
        best_fit = fit;
        source_from_target = inverse;
      }
    }
  }
  if (best_fit == 0 ||
      !RefineOnObservations(target, source, registered, loose_px,
                            &source_from_target) ||
      !RefineOnObservations(target, source, registered, max_px,
                            &source_from_target)) {
    result.reason = "no similarity fits the poses of the " +
                    std::to_string(result.num_registered_images) +
                    " source images registered on the target";
    return result;
  }
  int num_fit = 0;
  const auto support =
      Supporting(target, source, registered, source_from_target, max_px,
                 options, &num_fit);
  result.num_supporting_images = static_cast<int>(support.size());
  if (result.num_supporting_images < options.min_images ||
      2 * result.num_supporting_images < result.num_registered_images) {
    result.reason = "the similarity fits " +
                    std::to_string(result.num_supporting_images) + " of the " +
                    std::to_string(result.num_registered_images) +
                    " source images registered on the target";
    return result;
  }
  if (CenterSpread(source, support) < options.min_center_spread) {
    result.reason = "the " + std::to_string(result.num_supporting_images) +
                    " source images registered on the target stand at one "
                    "spot: the scale is unknown";
    return result;
  }
  result.target_from_source = colmap::Inverse(source_from_target);
  result.success = true;
  return result;
}

}  // namespace tmr
