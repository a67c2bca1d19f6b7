// Copyright (c) 2026, the tmr authors. BSD-3-Clause.
#include "merge/join_adjustment.h"

#include <colmap/geometry/pose.h>

#include <algorithm>
#include <unordered_set>

#include "sfm/block_adjustment.h"
#include "sfm/model_edits.h"

namespace tmr {

CompactTrackModel MakeCompactTrackModel(const colmap::Reconstruction& model,
                                        size_t points_per_image) {
  CompactTrackModel compact;
  const std::vector<colmap::point3D_t> kept =
      LongestTrackPoints(model, points_per_image);
  for (const colmap::point3D_t id : kept) {
    for (const colmap::TrackElement& element :
         model.Point3D(id).track.Elements())
      compact.original_index[element.image_id].push_back(element.point2D_idx);
  }
  for (const colmap::image_t id : model.RegImageIds()) {
    const colmap::Image& image = model.Image(id);
    AddImageWithoutPoints(model, id, image.CamFromWorld(), &compact.model,
                          /*with_keypoints=*/false);
    std::vector<colmap::point2D_t>& index = compact.original_index[id];
    std::sort(index.begin(), index.end());
    std::vector<Eigen::Vector2d> xy;
    xy.reserve(index.size());
    for (const colmap::point2D_t j : index) xy.push_back(image.Point2D(j).xy);
    compact.model.Image(id).SetPoints2D(xy);
  }
  for (const colmap::point3D_t id : kept) {
    const colmap::Point3D& point = model.Point3D(id);
    colmap::Track track;
    for (const colmap::TrackElement& element : point.track.Elements()) {
      const std::vector<colmap::point2D_t>& index =
          compact.original_index.at(element.image_id);
      track.AddElement(
          element.image_id,
          std::lower_bound(index.begin(), index.end(), element.point2D_idx) -
              index.begin());
    }
    compact.model.AddPoint3D(point.xyz, std::move(track), point.color);
  }
  return compact;
}

void JoinAdjustment::AddPiece(const CompactTrackModel& piece,
                              const colmap::Sim3d& scene_from_piece,
                              const std::vector<colmap::image_t>& dropped) {
  const std::unordered_set<colmap::image_t> left_out(dropped.begin(),
                                                     dropped.end());
  for (const colmap::image_t id : piece.model.RegImageIds()) {
    if (left_out.count(id) || scene_.ExistsImage(id)) continue;
    AddImageWithoutPoints(
        piece.model, id,
        colmap::TransformCameraWorld(scene_from_piece,
                                     piece.model.Image(id).CamFromWorld()),
        &scene_, /*with_keypoints=*/false);
  }
  for (const auto& [point_id, point] : piece.model.Points3D()) {
    const int index = static_cast<int>(points_.size());
    points_.push_back({scene_from_piece * point.xyz, {}, -1});
    for (const colmap::TrackElement& element : point.track.Elements()) {
      const colmap::point2D_t keypoint =
          piece.original_index.at(element.image_id).at(element.point2D_idx);
      const uint64_t key =
          (static_cast<uint64_t>(element.image_id) << 32) | keypoint;
      const auto [it, inserted] = point_of_keypoint_.emplace(key, index);
      if (inserted) {
        points_[index].observations.push_back(observations_.size());
        observations_.push_back({element.image_id, keypoint,
                                 piece.model.Image(element.image_id)
                                     .Point2D(element.point2D_idx)
                                     .xy});
        continue;
      }
      const int mine = Root(index), theirs = Root(it->second);
      if (mine == theirs) continue;
      points_[mine].joined_into = theirs;
      ++num_joined_points_;
    }
  }
}

int JoinAdjustment::Root(int point) {
  int root = point;
  while (points_[root].joined_into >= 0) root = points_[root].joined_into;
  while (points_[point].joined_into >= 0) {
    const int next = points_[point].joined_into;
    points_[point].joined_into = root;
    point = next;
  }
  return root;
}

std::string JoinAdjustment::Adjust(colmap::BundleAdjustmentOptions options) {
  // Each image's keypoints in the order their observations came, then each
  // joined point one track with at most one keypoint per image.
  std::vector<colmap::point2D_t> slot(observations_.size(), 0);
  std::unordered_map<colmap::image_t, std::vector<Eigen::Vector2d>> keypoints;
  for (size_t o = 0; o < observations_.size(); ++o) {
    if (!scene_.ExistsImage(observations_[o].image_id)) continue;
    std::vector<Eigen::Vector2d>& xy = keypoints[observations_[o].image_id];
    slot[o] = static_cast<colmap::point2D_t>(xy.size());
    xy.push_back(observations_[o].xy);
  }
  for (auto& [id, xy] : keypoints) scene_.Image(id).SetPoints2D(xy);
  keypoints.clear();
  std::unordered_map<int, std::vector<int>> members;
  for (int p = 0; p < static_cast<int>(points_.size()); ++p)
    members[Root(p)].push_back(p);
  for (const auto& [root, joined] : members) {
    colmap::Track track;
    for (const int p : joined) {
      for (const size_t o : points_[p].observations) {
        const colmap::image_t id = observations_[o].image_id;
        if (!scene_.ExistsImage(id)) continue;
        const auto& elements = track.Elements();
        if (std::any_of(elements.begin(), elements.end(),
                        [id](const colmap::TrackElement& element) {
                          return element.image_id == id;
                        }))
          continue;
        track.AddElement(id, slot[o]);
      }
    }
    if (track.Length() >= 2) scene_.AddPoint3D(points_[root].xyz, track);
  }
  members.clear();
  points_ = {};
  observations_ = {};
  point_of_keypoint_ = {};
  options.refine_focal_length = false;
  options.refine_principal_point = false;
  options.refine_extra_params = false;
  std::string report =
      "on " + std::to_string(scene_.NumPoints3D()) + " points (" +
      std::to_string(num_joined_points_) +
      " joined across models): " + AdjustWholeModel(options, &scene_);
  for (const colmap::image_t id : scene_.RegImageIds())
    adjusted_[id] = scene_.Image(id).CamFromWorld();
  scene_ = colmap::Reconstruction();
  return report;
}

void JoinAdjustment::MoveToAdjustedPoses(colmap::Reconstruction* piece,
                                         int num_threads) const {
  std::vector<colmap::point3D_t> point_ids;
  point_ids.reserve(piece->NumPoints3D());
  for (const auto& [point_id, point] : piece->Points3D())
    point_ids.push_back(point_id);
  MoveToPoses(adjusted_, point_ids, piece, num_threads);
}

}  // namespace tmr
