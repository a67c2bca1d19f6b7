// Copyright (c) 2026, the tmr authors. BSD-3-Clause.
#include "merge/shared_track_alignment.h"

#include <colmap/estimators/solvers/similarity_transform.h>
#include <colmap/optim/loransac.h>

#include <algorithm>
#include <sstream>
#include <string>
#include <unordered_set>
#include <vector>

namespace tmr {
namespace {

using Sim3Ransac =
    colmap::LORANSAC<colmap::SimilarityTransformEstimator<3, true>,
                     colmap::SimilarityTransformEstimator<3, true>>;

struct SharedTrack {
  Eigen::Vector3d target_xyz;
  Eigen::Vector3d source_xyz;
  double viewing_distance;       // from the target camera that sees it
  colmap::image_t target_image;  // a target image observing the track
  Eigen::Vector2d target_xy;     // its observation there
  colmap::image_t source_image;  // the source image the track came from
};

// The tracks of a source image that are reconstructed in the target.
std::vector<SharedTrack> SharedTracks(const colmap::Reconstruction& target,
                                      const colmap::Reconstruction& source,
                                      const colmap::CorrespondenceGraph& graph,
                                      colmap::image_t source_image) {
  std::vector<SharedTrack> shared;
  if (!graph.ExistsImage(source_image)) return shared;
  const colmap::Image& image = source.Image(source_image);
  for (colmap::point2D_t idx = 0; idx < image.NumPoints2D(); ++idx) {
    const colmap::Point2D& point2D = image.Point2D(idx);
    if (!point2D.HasPoint3D()) continue;
    const auto range = graph.FindCorrespondences(source_image, idx);
    for (auto it = range.beg; it != range.end; ++it) {
      if (!target.ExistsImage(it->image_id) ||
          !target.Image(it->image_id).HasPose())
        continue;
      const colmap::Image& other = target.Image(it->image_id);
      const colmap::Point2D& match = other.Point2D(it->point2D_idx);
      if (!match.HasPoint3D()) continue;
      const Eigen::Vector3d xyz = target.Point3D(match.point3D_id).xyz;
      shared.push_back({xyz, source.Point3D(point2D.point3D_id).xyz,
                        (xyz - other.ProjectionCenter()).norm(), it->image_id,
                        match.xy, source_image});
      break;  // one target point per source track
    }
  }
  return shared;
}

// Similarity from the 3D-3D pairs of shared tracks: Umeyama's method inside
// COLMAP's LO-RANSAC, with an inlier threshold relative to the median
// viewing distance.
Sim3Ransac::Report EstimateSimilarity(const std::vector<SharedTrack>& tracks,
                                      const ModelAlignmentOptions& options) {
  std::vector<Eigen::Vector3d> src, tgt;
  std::vector<double> distances;
  for (const SharedTrack& t : tracks) {
    src.push_back(t.source_xyz);
    tgt.push_back(t.target_xyz);
    distances.push_back(t.viewing_distance);
  }
  std::nth_element(distances.begin(), distances.begin() + distances.size() / 2,
                   distances.end());
  colmap::RANSACOptions ransac;
  ransac.max_error =
      options.max_relative_error * distances[distances.size() / 2];
  ransac.min_inlier_ratio = options.min_inlier_ratio;
  ransac.max_num_trials = 5000;
  ransac.random_seed = static_cast<int>(options.seed);
  Sim3Ransac estimator(ransac);
  return estimator.Estimate(src, tgt);
}

// Whether the source point of `t`, moved into the target, reprojects onto
// its target observation within max_px.
bool Reprojects(const colmap::Reconstruction& target, const colmap::Sim3d& sim,
                const SharedTrack& t, double max_px) {
  const colmap::Image& image = target.Image(t.target_image);
  const Eigen::Vector3d in_camera = image.CamFromWorld() * (sim * t.source_xyz);
  if (in_camera.z() <= 0) return false;
  const std::optional<Eigen::Vector2d> xy =
      target.Camera(image.CameraId()).ImgFromCam(in_camera);
  return xy && (*xy - t.target_xy).norm() <= max_px;
}

}  // namespace

SharedTrackFit FitSharedTracks(const colmap::Reconstruction& target,
                               const colmap::Reconstruction& source,
                               const colmap::CorrespondenceGraph& graph,
                               const colmap::Sim3d& target_from_source,
                               double max_reprojection_error_px) {
  SharedTrackFit fit;
  for (const colmap::image_t image_id : source.RegImageIds()) {
    if (target.ExistsImage(image_id) && target.Image(image_id).HasPose())
      continue;
    for (const SharedTrack& t : SharedTracks(target, source, graph, image_id)) {
      ++fit.num_shared;
      fit.num_fit +=
          Reprojects(target, target_from_source, t, max_reprojection_error_px);
    }
  }
  return fit;
}

ModelAlignment AlignModelsBySharedTracks(
    const colmap::Reconstruction& target, const colmap::Reconstruction& source,
    const colmap::CorrespondenceGraph& graph,
    const ModelAlignmentOptions& options) {
  ModelAlignment result;
  std::vector<SharedTrack> best, all;
  for (const colmap::image_t image_id : source.RegImageIds()) {
    if (target.ExistsImage(image_id) && target.Image(image_id).HasPose())
      continue;
    std::vector<SharedTrack> shared =
        SharedTracks(target, source, graph, image_id);
    all.insert(all.end(), shared.begin(), shared.end());
    if (shared.size() > best.size()) {
      best = std::move(shared);
      result.anchor_image = image_id;
    }
  }
  result.num_shared_tracks = static_cast<int>(best.size());
  if (result.num_shared_tracks <= options.min_shared_tracks) {
    result.reason = "best image shares " +
                    std::to_string(result.num_shared_tracks) +
                    " tracks (needs more than " +
                    std::to_string(options.min_shared_tracks) + ")";
    return result;
  }
  // The paper's estimate, from the anchor image's tracks alone.
  const auto anchor_estimate = EstimateSimilarity(best, options);
  result.num_inliers = static_cast<int>(anchor_estimate.support.num_inliers);
  if (!anchor_estimate.success ||
      result.num_inliers <= options.min_shared_tracks ||
      result.num_inliers < options.min_inlier_ratio * best.size()) {
    result.reason =
        "no similarity fits: " + std::to_string(result.num_inliers) + " of " +
        std::to_string(best.size()) + " shared tracks agree";
    return result;
  }
  // The anchor image's tracks cover a small patch of the scene, and a
  // similarity fitted to a patch tilts away from it; the final estimate uses
  // the shared tracks of every image, which span the whole overlap.
  const auto estimate = EstimateSimilarity(all, options);
  if (!estimate.success) {
    result.reason = "no similarity fits the shared tracks of all images";
    return result;
  }
  // Verification: the source point, moved into the target, must reproject
  // onto its target observation. Some shared tracks are wrong whatever the
  // transform (a correspondence can be an outlier that passed two-view
  // verification), so the other images are held to the anchor image's own
  // rate under the same test rather than to a fixed one: a wrong merge
  // (repetitive structure, a false pair) fits the anchor image alone.
  const colmap::Sim3d sim = colmap::Sim3d::FromMatrix(estimate.model);
  const double max_px = options.max_reprojection_error_px;
  int anchor_fit = 0, other_fit = 0, others = 0;
  for (const SharedTrack& t : best)
    anchor_fit += Reprojects(target, sim, t, max_px);
  for (const SharedTrack& t : all) {
    if (t.source_image == result.anchor_image) continue;
    ++others;
    other_fit += Reprojects(target, sim, t, max_px);
  }
  const double anchor_rate = static_cast<double>(anchor_fit) / best.size();
  result.num_verified = other_fit;
  if (other_fit <= options.min_shared_tracks ||
      other_fit < options.min_relative_support * anchor_rate * others) {
    std::ostringstream reason;
    reason << std::fixed;
    reason.precision(0);
    reason << "the similarity fits the anchor image (" << anchor_rate * 100
           << "% of its tracks reproject within "
           << options.max_reprojection_error_px << " px) but only " << other_fit
           << " of the " << others << " shared tracks of the other images do";
    result.reason = reason.str();
    return result;
  }
  result.target_from_source = sim;
  result.success = true;
  return result;
}

}  // namespace tmr
