// Copyright (c) 2026, the tmr authors. BSD-3-Clause.
//
// Edits of a COLMAP model that the adjustments and the merges share.
#pragma once

#include <colmap/geometry/sim3.h>
#include <colmap/scene/reconstruction.h>

#include <unordered_map>
#include <unordered_set>
#include <vector>

namespace tmr {

// Adds image `image_id` of `source` to `target` (id, name, camera,
// keypoints unless `with_keypoints` is false, none of them on a 3D point;
// its camera, rig and frame too where `target` lacks them), posed at
// cam_from_world and registered.
void AddImageWithoutPoints(const colmap::Reconstruction& source,
                           colmap::image_t image_id,
                           const colmap::Rigid3d& cam_from_world,
                           colmap::Reconstruction* target,
                           bool with_keypoints = true);

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

// KeepOneCopyOfEachImage's rule on each model's registered images and their
// numbers of 3D points (models in order, the whole models or only the
// images another model may hold): per model, the images whose copy in
// another model stays (the copy with the most 3D points, the first
// model's on a tie), sorted.
std::vector<std::vector<colmap::image_t>> DroppedImageCopies(
    const std::vector<std::unordered_map<colmap::image_t, size_t>>&
        points_of_images);

// Leaves every image registered in one of `models` only: where several
// register it (the halo of neighbouring clusters), the copy that observes
// the most 3D points stays (the first model's on a tie) and the others are
// deregistered, their observations taken out of their tracks. Returns how
// many copies it deregistered; `dropped` (may be null) receives, per model,
// the images deregistered from it.
int KeepOneCopyOfEachImage(
    const std::vector<colmap::Reconstruction*>& models,
    std::vector<std::vector<colmap::image_t>>* dropped = nullptr);

// Makes `seam_model` (empty) a light copy of `model` that aligns with
// other models as `model` would on a seam between them (the join of a
// merge stage by parts): every registered image at its pose, but only
// `seam_images` with keypoints, and the points that those observe, their
// tracks cut to them. Each seam image keeps its number of 3D points, so
// KeepOneCopyOfEachImage decides on such copies as on the whole models.
void MakeSeamModel(const colmap::Reconstruction& model,
                   const std::unordered_set<colmap::image_t>& seam_images,
                   colmap::Reconstruction* seam_model);

// Adds the registered images of `source` that `target` does not hold,
// transformed by target_from_source, with their 3D points (observations in
// already held images are left to RefineMergedModel to re-link).
void AppendReconstruction(const colmap::Reconstruction& source,
                          const colmap::Sim3d& target_from_source,
                          colmap::Reconstruction* target);

}  // namespace tmr
