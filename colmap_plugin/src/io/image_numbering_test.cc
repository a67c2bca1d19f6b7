// Copyright (c) 2026, the tmr authors. BSD-3-Clause.
// NumberImagesByName on databases written with COLMAP's Database class as
// its feature extraction writes them, with images in the order their
// threads finished: ids follow the names afterwards, and each image keeps
// its camera, frame, keypoints, descriptors and pose prior.
#include "io/image_numbering.h"

#include <colmap/scene/database.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

namespace tmr {
namespace {

namespace fs = std::filesystem;

class ImageNumberingTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("image_numbering_test_" + std::to_string(::getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
    path_ = (dir_ / "database.db").string();
  }
  void TearDown() override { fs::remove_all(dir_); }

  // Images "c.jpg", "a.jpg", "b.jpg" (ids 1, 2, 3) as COLMAP's extraction
  // writes them: a camera and rig each, a frame each, 10 + id keypoints
  // and descriptors of the value id, and a gravity prior for "a.jpg".
  void WriteShuffledImages() {
    const auto database = colmap::Database::Open(path_);
    colmap::DatabaseTransaction transaction(database.get());
    for (const char* name : {"c.jpg", "a.jpg", "b.jpg"}) {
      colmap::Camera camera = colmap::Camera::CreateFromModelName(
          colmap::kInvalidCameraId, "SIMPLE_RADIAL", 500, 640, 480);
      camera.camera_id = database->WriteCamera(camera);
      colmap::Rig rig;
      rig.AddRefSensor(camera.SensorId());
      const colmap::rig_t rig_id = database->WriteRig(rig);
      colmap::Image image;
      image.SetName(name);
      image.SetCameraId(camera.camera_id);
      image.SetImageId(database->WriteImage(image));
      colmap::Frame frame;
      frame.SetRigId(rig_id);
      frame.AddDataId(image.DataId());
      database->WriteFrame(frame);
      const int n = 10 + static_cast<int>(image.ImageId());
      database->WriteKeypoints(image.ImageId(), colmap::FeatureKeypoints(n));
      colmap::FeatureDescriptors descriptors;
      descriptors.type = colmap::FeatureExtractorType::SIFT;
      descriptors.data.setConstant(n, 128, image.ImageId());
      database->WriteDescriptors(image.ImageId(), descriptors);
      if (std::string(name) == "a.jpg") {
        colmap::PosePrior prior;
        prior.corr_data_id = image.DataId();
        prior.gravity = Eigen::Vector3d(0, 1, 0);
        database->WritePosePrior(prior);
      }
    }
  }

  fs::path dir_;
  std::string path_;
};

TEST_F(ImageNumberingTest, IdsFollowNamesAndEverythingFollowsTheImages) {
  WriteShuffledImages();
  // A partial copy left by a killed run is not a database.
  std::ofstream(path_ + ".numbering") << "half a copy";
  bool renumbered = false;
  std::string error;
  ASSERT_TRUE(NumberImagesByName(path_, &renumbered, &error)) << error;
  EXPECT_TRUE(renumbered);
  EXPECT_FALSE(fs::exists(path_ + ".numbering"));

  const auto database = colmap::Database::Open(path_);
  ASSERT_EQ(database->NumImages(), 3u);
  EXPECT_EQ(database->NumFrames(), 3u);
  EXPECT_EQ(database->NumCameras(), 3u);
  EXPECT_EQ(database->NumRigs(), 3u);
  // (old id, old camera) by name: a.jpg 2, b.jpg 3, c.jpg 1.
  const std::vector<std::pair<std::string, int>> expected = {
      {"a.jpg", 2}, {"b.jpg", 3}, {"c.jpg", 1}};
  for (int i = 0; i < 3; ++i) {
    const colmap::image_t id = i + 1;
    const colmap::Image image = database->ReadImage(id);
    const int old_id = expected[i].second;
    EXPECT_EQ(image.Name(), expected[i].first);
    EXPECT_EQ(image.CameraId(), static_cast<colmap::camera_t>(old_id));
    EXPECT_EQ(database->ReadKeypoints(id).size(), 10u + old_id);
    const colmap::FeatureDescriptors descriptors =
        database->ReadDescriptors(id);
    EXPECT_EQ(descriptors.type, colmap::FeatureExtractorType::SIFT);
    ASSERT_EQ(descriptors.data.rows(), 10 + old_id);
    EXPECT_EQ(descriptors.data(0, 0), old_id);
    ASSERT_TRUE(image.HasFrameId());
    EXPECT_EQ(image.FrameId(), id);  // frames in the order of their images
    const colmap::Frame frame = database->ReadFrame(image.FrameId());
    EXPECT_TRUE(frame.HasDataId(image.DataId()));
    EXPECT_EQ(frame.RigId(), static_cast<colmap::rig_t>(old_id));
  }
  const std::vector<colmap::PosePrior> priors = database->ReadAllPosePriors();
  ASSERT_EQ(priors.size(), 1u);
  EXPECT_EQ(priors[0].corr_data_id.id, 1u);  // a.jpg
  EXPECT_TRUE(priors[0].HasGravity());
  database->Close();

  // Already in name order: left as it is.
  ASSERT_TRUE(NumberImagesByName(path_, &renumbered, &error)) << error;
  EXPECT_FALSE(renumbered);
}

TEST_F(ImageNumberingTest, DatabaseWithMatchesIsLeftAsItIs) {
  WriteShuffledImages();
  {
    const auto database = colmap::Database::Open(path_);
    database->WriteMatches(1, 2, colmap::FeatureMatches(5));
  }
  bool renumbered = true;
  std::string error;
  ASSERT_TRUE(NumberImagesByName(path_, &renumbered, &error)) << error;
  EXPECT_FALSE(renumbered);
  const auto database = colmap::Database::Open(path_);
  EXPECT_EQ(database->ReadImage(1).Name(), "c.jpg");
  EXPECT_EQ(database->NumMatchedImagePairs(), 1u);
}

TEST_F(ImageNumberingTest, MissingDatabaseIsAnErrorAndNotCreated) {
  bool renumbered = true;
  std::string error;
  EXPECT_FALSE(NumberImagesByName(path_, &renumbered, &error));
  EXPECT_NE(error.find("does not exist"), std::string::npos) << error;
  EXPECT_FALSE(renumbered);
  EXPECT_FALSE(fs::exists(path_));
}

}  // namespace
}  // namespace tmr
