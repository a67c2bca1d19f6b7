// Copyright (c) 2026, the tmr authors. BSD-3-Clause.
#include "sfm/match_consistency.h"

#include <colmap/geometry/triangulation.h>
#include <colmap/math/math.h>
#include <colmap/scene/projection.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <unordered_map>
#include <utility>
#include <vector>

namespace tmr {

bool MatchConsistencyOptions::Check(std::string* error) const {
  const auto fail = [error](const char* message) {
    if (error) *error = message;
    return false;
  };
  if (!(max_reprojection_error > 0.0 && std::isfinite(max_reprojection_error)))
    return fail("max_reprojection_error must be > 0");
  // Angles between two rays are at most 90 degrees (COLMAP's
  // CalculateTriangulationAngle).
  if (!(min_triangulation_angle_deg >= 0.0 &&
        min_triangulation_angle_deg < 90.0))
    return fail("min_triangulation_angle_deg must be in [0, 90)");
  if (!(max_inconsistent_share >= 0.0 && max_inconsistent_share <= 1.0))
    return fail("max_inconsistent_share must be in [0, 1]");
  if (max_inconsistent_pairs < 0 || min_pair_matches < 1)
    return fail("max_inconsistent_pairs must be >= 0, min_pair_matches >= 1");
  return true;
}

namespace {

// A keypoint as one number: image id in the high half, keypoint index in
// the low half.
uint64_t KeypointKey(colmap::image_t image_id, colmap::point2D_t point2D_idx) {
  return (static_cast<uint64_t>(image_id) << 32) | point2D_idx;
}

// The verified matches of the model's registered pairs that no common track
// holds, as pairs of keypoint keys, and of every keypoint among them the
// keypoints that verified matches of any pair link it to.
struct OpenMatches {
  std::unordered_map<uint64_t, std::vector<uint64_t>> linked;
  bool Confirmed(uint64_t key1, uint64_t key2) const {
    const std::vector<uint64_t>& links1 = linked.at(key1);
    const std::vector<uint64_t>& links2 = linked.at(key2);
    for (const uint64_t key : links1) {
      if (key != key2 &&
          std::find(links2.begin(), links2.end(), key) != links2.end())
        return true;
    }
    return false;
  }
};

bool InCommonTrack(const colmap::Point2D& p1, const colmap::Point2D& p2) {
  return p1.HasPoint3D() && p1.point3D_id == p2.point3D_id;
}

bool RegisteredPair(const colmap::Reconstruction& model, colmap::image_t id1,
                    colmap::image_t id2) {
  return model.ExistsImage(id1) && model.ExistsImage(id2) &&
         model.Image(id1).HasPose() && model.Image(id2).HasPose();
}

// The links of the keypoints of the open matches (two passes over the
// matches: the keypoints first, so that memory grows with the open matches,
// not with the database).
OpenMatches LinkOpenMatches(
    const colmap::Reconstruction& model,
    const std::vector<std::pair<colmap::image_pair_t, colmap::TwoViewGeometry>>&
        geometries) {
  OpenMatches open;
  for (const auto& [pair_id, geometry] : geometries) {
    const auto [id1, id2] = colmap::PairIdToImagePair(pair_id);
    if (!RegisteredPair(model, id1, id2)) continue;
    const colmap::Image& image1 = model.Image(id1);
    const colmap::Image& image2 = model.Image(id2);
    for (const colmap::FeatureMatch& match : geometry.inlier_matches) {
      if (match.point2D_idx1 >= image1.NumPoints2D() ||
          match.point2D_idx2 >= image2.NumPoints2D() ||
          InCommonTrack(image1.Point2D(match.point2D_idx1),
                        image2.Point2D(match.point2D_idx2)))
        continue;
      open.linked.emplace(KeypointKey(id1, match.point2D_idx1),
                          std::vector<uint64_t>());
      open.linked.emplace(KeypointKey(id2, match.point2D_idx2),
                          std::vector<uint64_t>());
    }
  }
  for (const auto& [pair_id, geometry] : geometries) {
    const auto [id1, id2] = colmap::PairIdToImagePair(pair_id);
    for (const colmap::FeatureMatch& match : geometry.inlier_matches) {
      const uint64_t key1 = KeypointKey(id1, match.point2D_idx1);
      const uint64_t key2 = KeypointKey(id2, match.point2D_idx2);
      if (auto it = open.linked.find(key1); it != open.linked.end())
        it->second.push_back(key2);
      if (auto it = open.linked.find(key2); it != open.linked.end())
        it->second.push_back(key1);
    }
  }
  return open;
}

}  // namespace

MatchConsistency CheckMatchConsistency(const colmap::Reconstruction& model,
                                       const colmap::Database& database,
                                       const MatchConsistencyOptions& options) {
  if (std::string error; !options.Check(&error))
    throw std::invalid_argument("CheckMatchConsistency: " + error);
  const double max_squared_error =
      options.max_reprojection_error * options.max_reprojection_error;
  const double min_angle =
      colmap::DegToRad(options.min_triangulation_angle_deg);
  MatchConsistency result;
  const auto geometries = database.ReadTwoViewGeometries();
  const OpenMatches open = options.require_third_view
                               ? LinkOpenMatches(model, geometries)
                               : OpenMatches();
  for (const auto& [pair_id, geometry] : geometries) {
    const auto [id1, id2] = colmap::PairIdToImagePair(pair_id);
    const auto& matches = geometry.inlier_matches;
    if (matches.empty() || !RegisteredPair(model, id1, id2)) continue;
    const colmap::Image& image1 = model.Image(id1);
    const colmap::Image& image2 = model.Image(id2);
    const colmap::Camera& camera1 = model.Camera(image1.CameraId());
    const colmap::Camera& camera2 = model.Camera(image2.CameraId());
    const Eigen::Matrix3x4d pose1 = image1.CamFromWorld().ToMatrix();
    const Eigen::Matrix3x4d pose2 = image2.CamFromWorld().ToMatrix();
    const Eigen::Vector3d center1 = image1.ProjectionCenter();
    const Eigen::Vector3d center2 = image2.ProjectionCenter();
    ++result.num_pairs;
    int tested = 0, inconsistent = 0;
    for (const colmap::FeatureMatch& match : matches) {
      if (match.point2D_idx1 >= image1.NumPoints2D() ||
          match.point2D_idx2 >= image2.NumPoints2D())
        continue;  // keypoints of another database
      ++result.num_matches;
      const colmap::Point2D& p1 = image1.Point2D(match.point2D_idx1);
      const colmap::Point2D& p2 = image2.Point2D(match.point2D_idx2);
      if (InCommonTrack(p1, p2)) {
        ++result.num_in_common_track;
        continue;
      }
      if (options.require_third_view &&
          !open.Confirmed(KeypointKey(id1, match.point2D_idx1),
                          KeypointKey(id2, match.point2D_idx2))) {
        ++result.num_unconfirmed;
        continue;
      }
      const std::optional<Eigen::Vector2d> cam_point1 =
          camera1.CamFromImg(p1.xy);
      const std::optional<Eigen::Vector2d> cam_point2 =
          camera2.CamFromImg(p2.xy);
      Eigen::Vector3d xyz;
      // A match behind a camera cannot be placed at all: a wrong match
      // consistent with the epipolar geometry, not evidence against poses.
      if (!cam_point1 || !cam_point2 ||
          !colmap::TriangulatePoint(pose1, pose2, *cam_point1, *cam_point2,
                                    &xyz) ||
          !xyz.allFinite() || !colmap::HasPointPositiveDepth(pose1, xyz) ||
          !colmap::HasPointPositiveDepth(pose2, xyz))
        continue;
      if (colmap::CalculateTriangulationAngle(center1, center2, xyz) <
          min_angle) {
        ++result.num_low_angle;
        continue;
      }
      ++tested;
      if (colmap::CalculateSquaredReprojectionError(
              p1.xy, xyz, pose1, camera1) > max_squared_error ||
          colmap::CalculateSquaredReprojectionError(
              p2.xy, xyz, pose2, camera2) > max_squared_error)
        ++inconsistent;
    }
    result.num_tested += tested;
    result.num_inconsistent += inconsistent;
    if (tested >= options.min_pair_matches && 2 * inconsistent > tested)
      ++result.num_inconsistent_pairs;
  }
  return result;
}

}  // namespace tmr
