// Copyright (c) 2026, the tmr authors. BSD-3-Clause.
#include "sfm/model_edits.h"

#include <algorithm>
#include <stdexcept>
#include <unordered_map>
#include <unordered_set>
#include <utility>
#include <vector>

namespace tmr {

void AddImageWithoutPoints(const colmap::Reconstruction& source,
                           colmap::image_t image_id,
                           const colmap::Rigid3d& cam_from_world,
                           colmap::Reconstruction* target,
                           bool with_keypoints) {
  const colmap::Image& image = source.Image(image_id);
  if (!target->ExistsCamera(image.CameraId()))
    target->AddCamera(source.Camera(image.CameraId()));
  const colmap::rig_t rig_id = source.Frame(image.FrameId()).RigId();
  if (!target->ExistsRig(rig_id)) target->AddRig(source.Rig(rig_id));
  if (!target->ExistsFrame(image.FrameId())) {
    colmap::Frame frame = source.Frame(image.FrameId());
    frame.ResetRigPtr();
    frame.ResetPose();
    target->AddFrame(std::move(frame));
  }
  colmap::Image copy;
  copy.SetImageId(image.ImageId());
  copy.SetName(image.Name());
  copy.SetCameraId(image.CameraId());
  copy.SetFrameId(image.FrameId());
  std::vector<Eigen::Vector2d> xy;
  if (with_keypoints) {
    xy.reserve(image.NumPoints2D());
    for (const colmap::Point2D& p : image.Points2D()) xy.push_back(p.xy);
  }
  copy.SetPoints2D(xy);
  target->AddImage(std::move(copy));
  SetPoseAndRegister(image_id, cam_from_world, target);
}

void SetPoseAndRegister(colmap::image_t image_id,
                        const colmap::Rigid3d& cam_from_world,
                        colmap::Reconstruction* model) {
  const colmap::Image& image = model->Image(image_id);
  colmap::Frame& frame = model->Frame(image.FrameId());
  const bool registered = frame.HasPose();
  frame.SetCamFromWorld(image.CameraId(), cam_from_world);
  if (!registered) model->RegisterFrame(frame.FrameId());
}

void CopyPointsWithTracks(const colmap::Reconstruction& source,
                          const std::vector<colmap::point3D_t>& point_ids,
                          colmap::Reconstruction* target) {
  for (const colmap::point3D_t id : point_ids) {
    const colmap::Point3D& point = source.Point3D(id);
    for (const colmap::TrackElement& element : point.track.Elements()) {
      if (!target->ExistsImage(element.image_id)) {
        AddImageWithoutPoints(source, element.image_id,
                              source.Image(element.image_id).CamFromWorld(),
                              target);
      }
      target->Image(element.image_id)
          .SetPoint3DForPoint2D(element.point2D_idx, id);
    }
    target->AddPoint3D(id, point);
  }
}

std::vector<std::vector<colmap::image_t>> DroppedImageCopies(
    const std::vector<std::unordered_map<colmap::image_t, size_t>>&
        points_of_images) {
  // Per image, the model whose copy stays and its number of 3D points.
  std::unordered_map<colmap::image_t, std::pair<size_t, size_t>> best;
  for (size_t m = 0; m < points_of_images.size(); ++m) {
    for (const auto& [id, points] : points_of_images[m]) {
      const auto [it, inserted] = best.emplace(id, std::make_pair(m, points));
      if (!inserted && points > it->second.second) it->second = {m, points};
    }
  }
  std::vector<std::vector<colmap::image_t>> dropped(points_of_images.size());
  for (size_t m = 0; m < points_of_images.size(); ++m) {
    for (const auto& [id, points] : points_of_images[m])
      if (best.at(id).first != m) dropped[m].push_back(id);
    std::sort(dropped[m].begin(), dropped[m].end());
  }
  return dropped;
}

int KeepOneCopyOfEachImage(const std::vector<colmap::Reconstruction*>& models,
                           std::vector<std::vector<colmap::image_t>>* dropped) {
  std::vector<std::unordered_map<colmap::image_t, size_t>> points_of_images(
      models.size());
  for (size_t m = 0; m < models.size(); ++m) {
    for (const colmap::image_t id : models[m]->RegImageIds())
      points_of_images[m][id] = models[m]->Image(id).NumPoints3D();
  }
  std::vector<std::vector<colmap::image_t>> drop =
      DroppedImageCopies(points_of_images);
  int removed = 0;
  for (size_t m = 0; m < models.size(); ++m) {
    for (const colmap::image_t id : drop[m]) {
      models[m]->DeRegisterFrame(models[m]->Image(id).FrameId());
      ++removed;
    }
  }
  if (dropped) *dropped = std::move(drop);
  return removed;
}

void MakeSeamModel(const colmap::Reconstruction& model,
                   const std::unordered_set<colmap::image_t>& seam_images,
                   colmap::Reconstruction* seam) {
  for (const colmap::image_t id : model.RegImageIds()) {
    AddImageWithoutPoints(model, id, model.Image(id).CamFromWorld(), seam,
                          /*with_keypoints=*/seam_images.count(id) > 0);
  }
  for (const auto& [point_id, point] : model.Points3D()) {
    colmap::Point3D cut;
    cut.xyz = point.xyz;
    cut.color = point.color;
    cut.error = point.error;
    for (const colmap::TrackElement& element : point.track.Elements()) {
      if (seam_images.count(element.image_id)) cut.track.AddElement(element);
    }
    if (cut.track.Length() > 0) seam->AddPoint3D(point_id, std::move(cut));
  }
}

void AppendReconstruction(const colmap::Reconstruction& source,
                          const colmap::Sim3d& target_from_source,
                          colmap::Reconstruction* target) {
  colmap::Reconstruction moved = source;
  moved.Transform(target_from_source);
  std::unordered_set<colmap::image_t> added;
  for (const colmap::image_t image_id : moved.RegImageIds()) {
    const colmap::Image& image = moved.Image(image_id);
    if (target->ExistsImage(image_id)) {
      // A model a mapper has continued holds every image of the database,
      // most unregistered; such an image takes the source's pose.
      const colmap::Image& held = target->Image(image_id);
      if (held.HasPose()) continue;
      if (held.NumPoints2D() != image.NumPoints2D())
        throw std::logic_error(
            "AppendReconstruction: the models disagree on "
            "the keypoints of " +
            image.Name());
      SetPoseAndRegister(image_id, image.CamFromWorld(), target);
    } else {
      AddImageWithoutPoints(moved, image_id, image.CamFromWorld(), target);
    }
    added.insert(image_id);
  }
  for (const auto& [point_id, point] : moved.Points3D()) {
    colmap::Track track;
    for (const colmap::TrackElement& el : point.track.Elements()) {
      if (added.count(el.image_id)) track.AddElement(el);
    }
    if (track.Length() >= 2) target->AddPoint3D(point.xyz, track, point.color);
  }
}

}  // namespace tmr
