// Copyright (c) 2026, the tmr authors. BSD-3-Clause.
#include "sfm/model_edits.h"

#include <vector>

namespace tmr {

void AddImageWithoutPoints(const colmap::Reconstruction& source,
                           colmap::image_t image_id,
                           const colmap::Rigid3d& cam_from_world,
                           colmap::Reconstruction* target) {
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
  xy.reserve(image.NumPoints2D());
  for (const colmap::Point2D& p : image.Points2D()) xy.push_back(p.xy);
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

}  // namespace tmr
