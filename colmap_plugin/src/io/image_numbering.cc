// Copyright (c) 2026, the tmr authors. BSD-3-Clause.
#include "io/image_numbering.h"

#include <colmap/scene/database.h>

#include <algorithm>
#include <exception>
#include <filesystem>
#include <map>
#include <stdexcept>
#include <string>
#include <vector>

namespace tmr {
namespace {

namespace fs = std::filesystem;

// Images by name, and whether their ids (and those of their frames) already
// rise in that order.
bool InNameOrder(const std::vector<colmap::Image>& by_name) {
  for (size_t i = 1; i < by_name.size(); ++i) {
    if (by_name[i].ImageId() < by_name[i - 1].ImageId()) return false;
    if (by_name[i].HasFrameId() && by_name[i - 1].HasFrameId() &&
        by_name[i].FrameId() < by_name[i - 1].FrameId())
      return false;
  }
  return true;
}

// Writes the images of `source` in the order of `by_name`, with ids from 1,
// into the empty database `target`.
void CopyInNameOrder(const colmap::Database& source,
                     const std::vector<colmap::Image>& by_name,
                     colmap::Database* target) {
  colmap::DatabaseTransaction transaction(target);
  for (const colmap::Rig& rig : source.ReadAllRigs())
    target->WriteRig(rig, /*use_rig_id=*/true);
  for (const colmap::Camera& camera : source.ReadAllCameras())
    target->WriteCamera(camera, /*use_camera_id=*/true);

  std::map<colmap::image_t, colmap::image_t> new_image_id;
  for (size_t i = 0; i < by_name.size(); ++i)
    new_image_id[by_name[i].ImageId()] = static_cast<colmap::image_t>(i + 1);
  const auto renumbered = [&](colmap::data_t data_id) {
    if (data_id.sensor_id.type != colmap::SensorType::CAMERA) return data_id;
    const auto it = new_image_id.find(static_cast<colmap::image_t>(data_id.id));
    if (it == new_image_id.end())
      throw std::runtime_error("a frame or pose prior names image " +
                               std::to_string(data_id.id) +
                               ", which does not exist");
    data_id.id = it->second;
    return data_id;
  };

  // Frames in the order of their first image.
  std::map<colmap::frame_t, colmap::Frame> old_frames;
  for (colmap::Frame& frame : source.ReadAllFrames())
    old_frames.emplace(frame.FrameId(), std::move(frame));
  std::map<colmap::frame_t, colmap::frame_t> new_frame_id;
  for (const colmap::Image& image : by_name) {
    if (!image.HasFrameId() || new_frame_id.count(image.FrameId())) continue;
    const colmap::Frame& old_frame = old_frames.at(image.FrameId());
    colmap::Frame frame;
    frame.SetFrameId(static_cast<colmap::frame_t>(new_frame_id.size() + 1));
    frame.SetRigId(old_frame.RigId());
    for (const colmap::data_t& data_id : old_frame.DataIds())
      frame.AddDataId(renumbered(data_id));
    target->WriteFrame(frame, /*use_frame_id=*/true);
    new_frame_id[image.FrameId()] = frame.FrameId();
  }

  for (const colmap::Image& old_image : by_name) {
    colmap::Image image;
    image.SetImageId(new_image_id.at(old_image.ImageId()));
    image.SetName(old_image.Name());
    image.SetCameraId(old_image.CameraId());
    if (old_image.HasFrameId())
      image.SetFrameId(new_frame_id.at(old_image.FrameId()));
    target->WriteImage(image, /*use_image_id=*/true);
    if (source.ExistsKeypoints(old_image.ImageId()))
      target->WriteKeypoints(image.ImageId(),
                             source.ReadKeypointsBlob(old_image.ImageId()));
    if (source.ExistsDescriptors(old_image.ImageId()))
      target->WriteDescriptors(image.ImageId(),
                               source.ReadDescriptors(old_image.ImageId()));
  }

  // Pose priors (GPS, gravity) in the order of their images.
  std::vector<colmap::PosePrior> priors = source.ReadAllPosePriors();
  for (colmap::PosePrior& prior : priors)
    prior.corr_data_id = renumbered(prior.corr_data_id);
  std::sort(priors.begin(), priors.end(), [](const auto& a, const auto& b) {
    return a.corr_data_id.id < b.corr_data_id.id;
  });
  for (size_t i = 0; i < priors.size(); ++i) {
    priors[i].pose_prior_id = static_cast<colmap::pose_prior_t>(i + 1);
    target->WritePosePrior(priors[i], /*use_pose_prior_id=*/true);
  }
}

}  // namespace

bool NumberImagesByName(const std::string& database_path, bool* renumbered,
                        std::string* error) {
  if (renumbered) *renumbered = false;
  const fs::path path(database_path);
  const fs::path partial(database_path + ".numbering");
  if (!fs::is_regular_file(path)) {
    *error = "database '" + database_path + "' does not exist";
    return false;
  }
  try {
    std::error_code ec;
    for (const char* suffix : {"", "-wal", "-shm"})  // of a killed run
      fs::remove(partial.string() + suffix, ec);
    {
      std::shared_ptr<colmap::Database> source =
          colmap::Database::Open(database_path);
      if (source->NumMatchedImagePairs() > 0 ||
          source->NumVerifiedImagePairs() > 0)
        return true;
      std::vector<colmap::Image> by_name = source->ReadAllImages();
      std::sort(
          by_name.begin(), by_name.end(),
          [](const auto& a, const auto& b) { return a.Name() < b.Name(); });
      if (InNameOrder(by_name)) return true;
      std::shared_ptr<colmap::Database> target =
          colmap::Database::Open(partial);
      CopyInNameOrder(*source, by_name, target.get());
      target->Close();
      source->Close();
    }
    // Both closed, so SQLite has folded their write-ahead logs into the
    // files, unless another connection holds one open: a log left beside
    // the old file would be replayed onto the new one.
    if (fs::exists(database_path + "-wal") ||
        fs::exists(partial.string() + "-wal"))
      throw std::runtime_error("it is open in another process");
    fs::rename(partial, path);
  } catch (const std::exception& e) {
    std::error_code ec;
    fs::remove(partial, ec);
    *error = "cannot number the images of '" + database_path +
             "' by name: " + e.what();
    return false;
  }
  if (renumbered) *renumbered = true;
  return true;
}

}  // namespace tmr
