// Copyright (c) 2026, the tmr authors. BSD-3-Clause.
// MeasureForwardMotion on a database written by COLMAP's Database class:
// pairs with an essential matrix (calibrated) and with only a fundamental
// matrix (its epipole read through camera 2's focal length and principal
// point), moving forward or sideways; planar pairs are left out.
#include "sfm/forward_motion.h"

#include <colmap/geometry/essential_matrix.h>
#include <colmap/scene/two_view_geometry.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>

namespace tmr {
namespace {

namespace fs = std::filesystem;

constexpr double kFocal = 1000.0;

colmap::TwoViewGeometry Geometry(const Eigen::Vector3d& translation,
                                 bool calibrated) {
  const colmap::Rigid3d cam2_from_cam1(
      Eigen::Quaterniond(Eigen::AngleAxisd(0.05, Eigen::Vector3d::UnitY())),
      translation);
  const Eigen::Matrix3d E = colmap::EssentialMatrixFromPose(cam2_from_cam1);
  // Principal point off the origin (1200 x 800 photos): a fundamental
  // matrix read without it would put every epipole far from the centre.
  Eigen::Matrix3d K;
  K << kFocal, 0, 600, 0, kFocal, 400, 0, 0, 1;
  colmap::TwoViewGeometry geometry;
  geometry.F = colmap::FundamentalFromEssentialMatrix(K, E, K);
  if (calibrated) {
    geometry.config = colmap::TwoViewGeometry::CALIBRATED;
    geometry.E = E;
  } else {
    geometry.config = colmap::TwoViewGeometry::UNCALIBRATED;
  }
  geometry.inlier_matches = {{0, 0}, {1, 1}};
  return geometry;
}

class ForwardMotionTest : public ::testing::Test {
 protected:
  void SetUp() override {
    path_ = fs::temp_directory_path() /
            ("forward_motion_test_" + std::to_string(::getpid()) + ".db");
    fs::remove(path_);
    database_ = colmap::Database::Open(path_);
    colmap::Camera camera = colmap::Camera::CreateFromModelName(
        colmap::kInvalidCameraId, "SIMPLE_RADIAL", kFocal, 1200, 800);
    camera.has_prior_focal_length = true;
    const colmap::camera_t camera_id = database_->WriteCamera(camera);
    for (int i = 1; i <= 5; ++i) {
      colmap::Image image;
      image.SetName("image" + std::to_string(i) + ".jpg");
      image.SetCameraId(camera_id);
      ids_.push_back(database_->WriteImage(image));
    }
  }
  void TearDown() override {
    database_.reset();
    for (const char* suffix : {"", "-wal", "-shm"})
      fs::remove(path_.string() + suffix);
  }

  void Write(int i, int j, const colmap::TwoViewGeometry& geometry) {
    database_->WriteTwoViewGeometry(ids_[i], ids_[j], geometry);
  }

  fs::path path_;
  std::shared_ptr<colmap::Database> database_;
  std::vector<colmap::image_t> ids_;
};

TEST_F(ForwardMotionTest, CountsPairsMovingAlongTheViewingDirection) {
  Write(0, 1, Geometry({0.02, 0.0, -1.0}, /*calibrated=*/true));  // forward
  Write(0, 2, Geometry({0.0, 0.05, 1.0}, /*calibrated=*/false));  // forward
  Write(1, 2, Geometry({1.0, 0.0, 0.1}, /*calibrated=*/true));    // sideways
  Write(2, 3, Geometry({0.3, 1.0, 0.2}, /*calibrated=*/false));   // sideways
  colmap::TwoViewGeometry planar = Geometry({0, 0, 1}, true);
  planar.config = colmap::TwoViewGeometry::PLANAR;
  Write(0, 3, planar);

  ForwardMotionStats stats = MeasureForwardMotion(*database_, 0.95);
  EXPECT_EQ(stats.num_pairs, 4);
  EXPECT_EQ(stats.num_forward, 2);
  EXPECT_FALSE(stats.MovesForward(0.5));
  EXPECT_TRUE(stats.MovesForward(0.4));
  EXPECT_EQ(stats.num_cameras, 1);
  EXPECT_EQ(stats.num_cameras_with_prior_focal, 1);

  Write(3, 4, Geometry({-0.1, 0.1, 1.0}, /*calibrated=*/false));  // forward
  stats = MeasureForwardMotion(*database_, 0.95);
  EXPECT_EQ(stats.num_pairs, 5);
  EXPECT_EQ(stats.num_forward, 3);
  EXPECT_TRUE(stats.MovesForward(0.5));
  EXPECT_FALSE(stats.MovesForward(1.0));  // never more than every pair
}

}  // namespace
}  // namespace tmr
