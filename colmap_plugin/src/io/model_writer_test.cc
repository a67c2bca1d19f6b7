// Copyright (c) 2026, the tmr authors. BSD-3-Clause.
#include "io/model_writer.h"

#include <colmap/geometry/sim3.h>
#include <colmap/scene/synthetic.h>
#include <gtest/gtest.h>

#include <filesystem>

namespace tmr {
namespace {

namespace fs = std::filesystem;

// A COLMAP-synthesized model of 12 images on 2 cameras and rigs.
colmap::Reconstruction SynthesizedModel() {
  colmap::SyntheticDatasetOptions options;
  options.num_rigs = 2;
  options.num_frames_per_rig = 6;
  options.num_points3D = 150;
  options.track_length = 4;
  colmap::Reconstruction model;
  colmap::SynthesizeDataset(options, &model);
  return model;
}

// `model` with only the images for which `keep` holds registered.
template <typename Keep>
colmap::Reconstruction Registering(colmap::Reconstruction model, Keep keep) {
  for (const colmap::image_t id : model.RegImageIds()) {
    if (!keep(id)) model.DeRegisterFrame(model.Image(id).FrameId());
  }
  return model;
}

fs::path TestFolder(const std::string& name) {
  const fs::path dir =
      fs::temp_directory_path() / ("model_writer_test_" + name);
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

// Two parts of one model, their point ids overlapping and their cameras
// and rigs the same, the second moved by a similarity, written part by
// part, read back as one model: every image of each part where that part
// put it, with its points.
TEST(ModelWriter, PartsReadBackAsOneModel) {
  const colmap::Reconstruction whole = SynthesizedModel();
  const colmap::image_t middle = whole.RegImageIds()[whole.NumRegImages() / 2];
  const colmap::Reconstruction first =
      Registering(whole, [&](colmap::image_t id) { return id < middle; });
  const colmap::Reconstruction second =
      Registering(whole, [&](colmap::image_t id) { return id >= middle; });
  ASSERT_GT(first.NumPoints3D(), 0);
  ASSERT_GT(second.NumPoints3D(), 0);
  const colmap::Sim3d moved(
      2.0, Eigen::Quaterniond(Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitY())),
      Eigen::Vector3d(1, -2, 3));

  colmap::Reconstruction second_moved = second;
  second_moved.Transform(moved);

  const fs::path dir = TestFolder("parts");
  const std::string path = (dir / "0").string();
  ModelWriter writer(path);
  ASSERT_TRUE(writer.Open());
  colmap::Reconstruction part = first;
  ASSERT_TRUE(writer.Append(&part));
  part = second_moved;
  ASSERT_TRUE(writer.Append(&part));
  EXPECT_FALSE(fs::exists(path)) << "a model before Finish";
  ASSERT_TRUE(writer.Finish());
  EXPECT_FALSE(fs::exists(path + ".tmp"));

  colmap::Reconstruction written;
  written.ReadBinary(path);
  EXPECT_EQ(written.NumRegImages(), whole.NumRegImages());
  EXPECT_EQ(writer.NumRegImages(), whole.NumRegImages());
  EXPECT_EQ(written.NumCameras(), whole.NumCameras());
  EXPECT_EQ(written.NumRigs(), whole.NumRigs());
  EXPECT_EQ(written.NumPoints3D(), first.NumPoints3D() + second.NumPoints3D());
  EXPECT_EQ(written.ComputeNumObservations(),
            first.ComputeNumObservations() + second.ComputeNumObservations());
  for (const colmap::image_t id : whole.RegImageIds()) {
    const colmap::Image& image = written.Image(id);
    const colmap::Image& reference =
        id < middle ? first.Image(id) : second_moved.Image(id);
    EXPECT_EQ(image.NumPoints3D(), reference.NumPoints3D()) << image.Name();
    EXPECT_LT((image.ProjectionCenter() - reference.ProjectionCenter()).norm(),
              1e-9)
        << image.Name();
  }
  // Every observation points at a point whose track holds it.
  for (const auto& [point_id, point] : written.Points3D()) {
    for (const colmap::TrackElement& element : point.track.Elements()) {
      EXPECT_EQ(written.Image(element.image_id)
                    .Point2D(element.point2D_idx)
                    .point3D_id,
                point_id);
    }
  }
  fs::remove_all(dir);
}

// A camera comes from the first part that registers an image of it, not
// from a part that merely holds it (a model read from disk holds the
// cameras of all its images).
TEST(ModelWriter, ACameraComesFromAPartThatUsesIt) {
  const colmap::Reconstruction whole = SynthesizedModel();
  const colmap::camera_t second_camera =
      whole.Image(whole.RegImageIds().back()).CameraId();
  const auto of_camera = [&](bool second) {
    return [&, second](colmap::image_t id) {
      return (whole.Image(id).CameraId() == second_camera) == second;
    };
  };
  const colmap::Reconstruction first = Registering(whole, of_camera(false));
  colmap::Reconstruction second = Registering(whole, of_camera(true));
  second.Camera(second_camera).params[0] *= 1.1;
  ASSERT_GT(first.NumRegImages(), 0);
  ASSERT_GT(second.NumRegImages(), 0);

  const fs::path dir = TestFolder("cameras");
  const std::string path = (dir / "0").string();
  ModelWriter writer(path);
  ASSERT_TRUE(writer.Open());
  colmap::Reconstruction part = first;
  ASSERT_TRUE(writer.Append(&part));
  part = second;
  ASSERT_TRUE(writer.Append(&part));
  ASSERT_TRUE(writer.Finish());
  colmap::Reconstruction written;
  written.ReadBinary(path);
  EXPECT_EQ(written.NumRegImages(), whole.NumRegImages());
  EXPECT_EQ(written.Camera(second_camera).params[0],
            second.Camera(second_camera).params[0]);
  fs::remove_all(dir);
}

TEST(ModelWriter, AWriterThatDoesNotFinishLeavesNoModel) {
  const fs::path dir = TestFolder("unfinished");
  const std::string path = (dir / "0").string();
  {
    ModelWriter writer(path);
    ASSERT_TRUE(writer.Open());
    colmap::Reconstruction part = SynthesizedModel();
    ASSERT_TRUE(writer.Append(&part));
  }
  EXPECT_FALSE(fs::exists(path));
  EXPECT_FALSE(fs::exists(path + ".tmp"));
  fs::remove_all(dir);
}

}  // namespace
}  // namespace tmr
