// Copyright (c) 2026, the tmr authors. BSD-3-Clause.
// The adjustment of a joined scene of a merge stage by parts
// (docs/distributed.md): every pose adjusted together on the longest tracks
// of the groups' models, tied across the seams by the keypoints that
// several groups' copies of an image observe.
#pragma once

#include <colmap/estimators/bundle_adjustment.h>
#include <colmap/geometry/sim3.h>
#include <colmap/scene/reconstruction.h>

#include <cstdint>
#include <string>
#include <unordered_map>
#include <vector>

namespace tmr {

// A model reduced to the points among the longest tracks of some image
// (as ModelOfLongestTracks), its images holding only the keypoints those
// observe: a part of the model's memory that still fixes its large-scale
// shape. original_index[id][j] is the keypoint (point2D_idx in the model
// and the database) of image id's keypoint j.
struct CompactTrackModel {
  colmap::Reconstruction model;
  std::unordered_map<colmap::image_t, std::vector<colmap::point2D_t>>
      original_index;
};
CompactTrackModel MakeCompactTrackModel(const colmap::Reconstruction& model,
                                        size_t points_per_image);

// Bundle adjustment of a joined scene on its pieces' longest tracks, as the
// whole merge stage's adjustment on its longest tracks
// (AdjustOnLongestTracks) closes a scene's loops and fixes its large-scale
// shape, where a join by similarities alone moves each group as a rigid
// block and leaves each group bent as its own adjustment left it. Pieces
// are added in the scene's frame; an image that several pieces hold
// appears once, at its kept copy's pose, and the points of
// different pieces that observe the same keypoint of an image become one
// track (a track that would observe an image twice keeps the first
// keypoint): the seams' tracks tie the groups together. Intrinsics are held
// (each group refined its own). Afterwards, each piece's whole model takes
// the adjusted poses (MoveToAdjustedPoses).
class JoinAdjustment {
 public:
  // Adds `piece`, placed by scene_from_piece, without its `dropped` image
  // copies (their keypoints still tie its points to the kept copies).
  void AddPiece(const CompactTrackModel& piece,
                const colmap::Sim3d& scene_from_piece,
                const std::vector<colmap::image_t>& dropped);
  // Adjusts every pose and point of the scene made from the pieces (the
  // first two poses fix the gauge); returns a one-line report.
  std::string Adjust(colmap::BundleAdjustmentOptions options);
  // Points of one piece joined to those of another.
  size_t NumJoinedPoints() const { return num_joined_points_; }

  // Gives the registered images of `piece` (a whole model in the scene's
  // frame, dropped copies deregistered) their adjusted poses, its points
  // moved and triangulated again (MoveToPoses), on num_threads.
  void MoveToAdjustedPoses(colmap::Reconstruction* piece,
                           int num_threads = 1) const;

 private:
  struct Observation {
    colmap::image_t image_id;
    colmap::point2D_t keypoint;  // in the database
    Eigen::Vector2d xy;
  };
  struct Point {
    Eigen::Vector3d xyz;
    std::vector<size_t> observations;  // into observations_
    int joined_into = -1;              // another point of the same track
  };
  int Root(int point);  // with path compression

  // What the pieces added, until Adjust builds the scene from it.
  colmap::Reconstruction scene_;  // the kept images, placed; no keypoints
  std::vector<Observation> observations_;
  std::unordered_map<uint64_t, int> point_of_keypoint_;  // image, keypoint
  std::vector<Point> points_;
  size_t num_joined_points_ = 0;
  // After Adjust.
  std::unordered_map<colmap::image_t, colmap::Rigid3d> adjusted_;
};

}  // namespace tmr
