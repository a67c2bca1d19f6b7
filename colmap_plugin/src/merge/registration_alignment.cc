// Copyright (c) 2026, the tmr authors. BSD-3-Clause.
#include "merge/registration_alignment.h"

#include <ceres/ceres.h>
#include <colmap/estimators/pose.h>
#include <colmap/scene/projection.h>

#include <algorithm>
#include <cmath>

#include "merge/similarity_reprojection_cost.h"

namespace tmr {
namespace {

// The 2D-3D correspondences of one source image to the target's points:
// keypoint index and target point, one target point per keypoint.
struct TargetCorrespondences {
  colmap::image_t image_id = colmap::kInvalidImageId;
  std::vector<colmap::point2D_t> point2D_idx;
  std::vector<colmap::point3D_t> point3D_id;
};

TargetCorrespondences FindTargetCorrespondences(
    const colmap::Reconstruction& target, const colmap::Image& image,
    const colmap::CorrespondenceGraph& graph) {
  TargetCorrespondences c;
  c.image_id = image.ImageId();
  if (!graph.ExistsImage(image.ImageId())) return c;
  for (colmap::point2D_t idx = 0; idx < image.NumPoints2D(); ++idx) {
    const auto range = graph.FindCorrespondences(image.ImageId(), idx);
    for (auto it = range.beg; it != range.end; ++it) {
      if (!target.ExistsImage(it->image_id) ||
          !target.Image(it->image_id).HasPose())
        continue;
      const colmap::Point2D& match =
          target.Image(it->image_id).Point2D(it->point2D_idx);
      if (!match.HasPoint3D()) continue;
      c.point2D_idx.push_back(idx);
      c.point3D_id.push_back(match.point3D_id);
      break;
    }
  }
  return c;
}

// An image of the source registered on the target's points.
struct RegisteredImage {
  colmap::image_t image_id;
  colmap::Rigid3d target_cam_from_world;
  // Inlier correspondences: keypoint and target point.
  std::vector<std::pair<colmap::point2D_t, colmap::point3D_t>> inliers;
};

// COLMAP's registration of an image on known points
// (IncrementalMapper::RegisterNextImage), with the source's intrinsics
// held: P3P inside LO-RANSAC, then pose refinement on the inliers.
bool RegisterOnTarget(const colmap::Reconstruction& target,
                      const colmap::Reconstruction& source,
                      const TargetCorrespondences& c,
                      const RegistrationAlignmentOptions& options,
                      RegisteredImage* registered) {
  const colmap::Image& image = source.Image(c.image_id);
  colmap::Camera camera = source.Camera(image.CameraId());
  std::vector<Eigen::Vector2d> points2D;
  std::vector<Eigen::Vector3d> points3D;
  for (size_t k = 0; k < c.point2D_idx.size(); ++k) {
    points2D.push_back(image.Point2D(c.point2D_idx[k]).xy);
    points3D.push_back(target.Point3D(c.point3D_id[k]).xyz);
  }
  colmap::AbsolutePoseEstimationOptions estimation;
  estimation.estimate_focal_length = false;
  estimation.ransac_options.random_seed = static_cast<int>(options.seed);
  estimation.ransac_options.max_error = options.max_abs_pose_error_px;
  estimation.ransac_options.min_inlier_ratio = options.min_inlier_ratio;
  estimation.ransac_options.min_num_trials = 100;
  estimation.ransac_options.max_num_trials = 10000;
  estimation.ransac_options.confidence = 0.99999;
  colmap::Rigid3d cam_from_world;
  size_t num_inliers = 0;
  std::vector<char> inlier_mask;
  if (!colmap::EstimateAbsolutePose(estimation, points2D, points3D,
                                    &cam_from_world, &camera, &num_inliers,
                                    &inlier_mask) ||
      static_cast<int>(num_inliers) < options.min_num_inliers) {
    return false;
  }
  colmap::AbsolutePoseRefinementOptions refinement;
  refinement.refine_focal_length = false;
  refinement.refine_extra_params = false;
  if (!colmap::RefineAbsolutePose(refinement, inlier_mask, points2D, points3D,
                                  &cam_from_world, &camera)) {
    return false;
  }
  registered->image_id = c.image_id;
  registered->target_cam_from_world = cam_from_world;
  registered->inliers.clear();
  for (size_t k = 0; k < inlier_mask.size(); ++k) {
    if (inlier_mask[k])
      registered->inliers.emplace_back(c.point2D_idx[k], c.point3D_id[k]);
  }
  return true;
}

// An image that both models register (a halo image, which the tasks of two
// clusters registered): its target pose and its keypoints on the target's
// points, as a registration on the target would give them.
RegisteredImage SharedImage(const colmap::Reconstruction& target,
                            colmap::image_t image_id) {
  const colmap::Image& image = target.Image(image_id);
  RegisteredImage r{image_id, image.CamFromWorld(), {}};
  for (colmap::point2D_t idx = 0; idx < image.NumPoints2D(); ++idx) {
    const colmap::Point2D& p = image.Point2D(idx);
    if (p.HasPoint3D()) r.inliers.emplace_back(idx, p.point3D_id);
  }
  return r;
}

// The images of `source` that `target` registers too, with at least
// min_num_inliers points in the target, the most points first, at most
// max_images.
std::vector<RegisteredImage> SharedImages(
    const colmap::Reconstruction& target, const colmap::Reconstruction& source,
    const RegistrationAlignmentOptions& options) {
  std::vector<RegisteredImage> shared;
  for (const colmap::image_t image_id : source.RegImageIds()) {
    if (!target.ExistsImage(image_id) || !target.Image(image_id).HasPose())
      continue;
    RegisteredImage r = SharedImage(target, image_id);
    if (static_cast<int>(r.inliers.size()) >= options.min_num_inliers)
      shared.push_back(std::move(r));
  }
  std::sort(shared.begin(), shared.end(), [](const auto& a, const auto& b) {
    return a.inliers.size() != b.inliers.size()
               ? a.inliers.size() > b.inliers.size()
               : a.image_id < b.image_id;
  });
  if (static_cast<int>(shared.size()) > options.max_images)
    shared.resize(options.max_images);
  return shared;
}

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
  std::vector<TargetCorrespondences> candidates;
  for (const colmap::image_t image_id : source.RegImageIds()) {
    if (target.ExistsImage(image_id) && target.Image(image_id).HasPose())
      continue;
    TargetCorrespondences c =
        FindTargetCorrespondences(target, source.Image(image_id), graph);
    if (static_cast<int>(c.point2D_idx.size()) >= options.min_num_inliers)
      candidates.push_back(std::move(c));
  }
  std::sort(candidates.begin(), candidates.end(),
            [](const auto& a, const auto& b) {
              return a.point2D_idx.size() != b.point2D_idx.size()
                         ? a.point2D_idx.size() > b.point2D_idx.size()
                         : a.image_id < b.image_id;
            });
  if (!candidates.empty()) {
    result.anchor_image = candidates.front().image_id;
    result.num_shared_tracks =
        static_cast<int>(candidates.front().point2D_idx.size());
  }
  // Images both models hold need no registration.
  std::vector<RegisteredImage> registered =
      SharedImages(target, source, options);
  result.num_shared_images = static_cast<int>(registered.size());
  int tried = 0;
  for (const TargetCorrespondences& c : candidates) {
    if (static_cast<int>(registered.size()) >= options.max_images ||
        tried >= 3 * options.max_images)
      break;
    ++tried;
    RegisteredImage r;
    if (RegisterOnTarget(target, source, c, options, &r))
      registered.push_back(std::move(r));
  }
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
