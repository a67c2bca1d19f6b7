// Copyright (c) 2026, the tmr authors. BSD-3-Clause.
//
// Edits of a COLMAP model that the adjustments and the merges share.
#pragma once

#include <colmap/scene/reconstruction.h>

#include <vector>

namespace tmr {

// Adds image `image_id` of `source` to `target` (id, name, camera,
// keypoints, none of them on a 3D point; its camera, rig and frame too
// where `target` lacks them), posed at cam_from_world and registered.
void AddImageWithoutPoints(const colmap::Reconstruction& source,
                           colmap::image_t image_id,
                           const colmap::Rigid3d& cam_from_world,
                           colmap::Reconstruction* target);

// Poses image `image_id` of `model` (through its frame: tmr's frames hold
// one image each) and registers its frame if it was not.
void SetPoseAndRegister(colmap::image_t image_id,
                        const colmap::Rigid3d& cam_from_world,
                        colmap::Reconstruction* model);

// Adds the points `point_ids` of `source` to `target` with their ids and
// whole tracks; an image of a track that `target` lacks is added first, at
// its pose in `source` (AddImageWithoutPoints).
void CopyPointsWithTracks(const colmap::Reconstruction& source,
                          const std::vector<colmap::point3D_t>& point_ids,
                          colmap::Reconstruction* target);

// Leaves every image registered in one of `models` only: where several
// register it (the halo of neighbouring clusters), the copy that observes
// the most 3D points stays (the first model's on a tie) and the others are
// deregistered, their observations taken out of their tracks. Returns how
// many copies it deregistered.
int KeepOneCopyOfEachImage(const std::vector<colmap::Reconstruction*>& models);

}  // namespace tmr
