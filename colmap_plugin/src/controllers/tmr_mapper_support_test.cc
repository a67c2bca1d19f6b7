// Copyright (c) 2026, the tmr authors. BSD-3-Clause.
#include "controllers/tmr_mapper_support.h"

#include <colmap/scene/database.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>

namespace tmr {
namespace {

namespace fs = std::filesystem;

// A two-image database written by COLMAP's Database class.
fs::path WriteTwoImageDatabase() {
  const fs::path path = fs::temp_directory_path() /
                        ("tmr_fingerprint_" + std::to_string(getpid()) + ".db");
  fs::remove(path);
  const std::shared_ptr<colmap::Database> database =
      colmap::Database::Open(path.string());
  const colmap::camera_t camera = database->WriteCamera(
      colmap::Camera::CreateFromModelName(1, "SIMPLE_RADIAL", 500, 640, 480));
  for (const char* name : {"a.jpg", "b.jpg"}) {
    colmap::Image image;
    image.SetName(name);
    image.SetCameraId(camera);
    const colmap::image_t id = database->WriteImage(image);
    database->WriteKeypoints(id, colmap::FeatureKeypoints(20));
  }
  return path;
}

TEST(DatabaseContentHash, IgnoresCommitsThatChangeNoRowAndSeesNewMatches) {
  const fs::path path = WriteTwoImageDatabase();
  const uint64_t written = DatabaseContentHash(path.string());
  const std::string bytes = ReadFileToString(path.string());

  // COLMAP's tools open the database for writing (hierarchical_mapper
  // does): SQLite rewrites its change counters and the modification time.
  { colmap::Database::Open(path.string()); }
  fs::last_write_time(path, fs::file_time_type::clock::now());
  EXPECT_NE(ReadFileToString(path.string()), bytes);
  EXPECT_EQ(DatabaseContentHash(path.string()), written);

  {
    const std::shared_ptr<colmap::Database> database =
        colmap::Database::Open(path.string());
    colmap::TwoViewGeometry geometry;
    geometry.config = colmap::TwoViewGeometry::CALIBRATED;
    geometry.inlier_matches = colmap::FeatureMatches(15);
    for (colmap::point2D_t i = 0; i < 15; ++i)
      geometry.inlier_matches[i] = {i, i};
    database->WriteTwoViewGeometry(1, 2, geometry);
  }
  EXPECT_NE(DatabaseContentHash(path.string()), written);
  fs::remove(path);
}

TEST(DatabaseContentHash, DiffersForAMissingFile) {
  const fs::path path = WriteTwoImageDatabase();
  const uint64_t written = DatabaseContentHash(path.string());
  fs::remove(path);
  EXPECT_NE(DatabaseContentHash(path.string()), written);
}

}  // namespace
}  // namespace tmr
