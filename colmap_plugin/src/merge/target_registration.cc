// Copyright (c) 2026, the tmr authors. BSD-3-Clause.
#include "merge/target_registration.h"

#include <colmap/estimators/pose.h>

#include <algorithm>

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

}  // namespace

RegistrationOnTarget RegisterSourceImagesOnTarget(
    const colmap::Reconstruction& target, const colmap::Reconstruction& source,
    const colmap::CorrespondenceGraph& graph,
    const RegistrationAlignmentOptions& options) {
  RegistrationOnTarget result;
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
    result.anchor_correspondences =
        static_cast<int>(candidates.front().point2D_idx.size());
  }
  // Images both models hold need no registration.
  result.images = SharedImages(target, source, options);
  result.num_shared = static_cast<int>(result.images.size());
  for (const TargetCorrespondences& c : candidates) {
    if (static_cast<int>(result.images.size()) >= options.max_images ||
        result.num_tried >= 3 * options.max_images)
      break;
    ++result.num_tried;
    RegisteredImage r;
    if (RegisterOnTarget(target, source, c, options, &r))
      result.images.push_back(std::move(r));
  }
  return result;
}

}  // namespace tmr
