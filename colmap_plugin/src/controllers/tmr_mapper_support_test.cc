// Copyright (c) 2026, the tmr authors. BSD-3-Clause.
#include "controllers/tmr_mapper_support.h"

#include <colmap/scene/database.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <functional>
#include <utility>
#include <vector>

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

// Every option that reaches a kernel or leaf task must change the
// fingerprint, or a rerun with another value reuses tasks made with the old
// one; the options of later stages must not (a rerun reuses the tasks).
TEST(RunFingerprint, ChangesWithEveryOptionThatReachesATask) {
  using Change = std::pair<const char*, std::function<void(TmrMapperOptions*)>>;
  const std::vector<Change> task_changes = {
      {"min_num_matches", [](auto* o) { o->mapper.min_num_matches++; }},
      {"ignore_watermarks",
       [](auto* o) {
         o->mapper.ignore_watermarks = !o->mapper.ignore_watermarks;
       }},
      {"init_min_num_inliers",
       [](auto* o) { o->mapper.init_min_num_inliers++; }},
      {"min_model_size", [](auto* o) { o->mapper.min_model_size++; }},
      {"init_max_forward_motion",
       [](auto* o) { o->mapper.init_max_forward_motion /= 2; }},
      {"init_min_tri_angle", [](auto* o) { o->mapper.init_min_tri_angle++; }},
      {"filter_min_tri_angle",
       [](auto* o) { o->mapper.filter_min_tri_angle++; }},
      {"abs_pose_min_num_inliers",
       [](auto* o) { o->mapper.abs_pose_min_num_inliers++; }},
      {"filter_max_reproj_error",
       [](auto* o) { o->mapper.filter_max_reproj_error++; }},
      {"tri_min_angle", [](auto* o) { o->mapper.tri_min_angle++; }},
      {"ba_refine_focal_length",
       [](auto* o) {
         o->mapper.ba_refine_focal_length = !o->mapper.ba_refine_focal_length;
       }},
      {"ba_refine_principal_point",
       [](auto* o) {
         o->mapper.ba_refine_principal_point =
             !o->mapper.ba_refine_principal_point;
       }},
      {"ba_refine_extra_params",
       [](auto* o) {
         o->mapper.ba_refine_extra_params = !o->mapper.ba_refine_extra_params;
       }},
      {"ba_global_max_num_iterations",
       [](auto* o) { o->mapper.ba_global_max_num_iterations++; }},
      {"ba_global_max_refinements",
       [](auto* o) { o->mapper.ba_global_max_refinements++; }},
      {"ba_global_function_tolerance",
       [](auto* o) { o->mapper.ba_global_function_tolerance = 1e-6; }},
      {"ba_local_num_images", [](auto* o) { o->mapper.ba_local_num_images++; }},
      {"ba_local_max_num_iterations",
       [](auto* o) { o->mapper.ba_local_max_num_iterations++; }},
      {"ba_local_max_refinements",
       [](auto* o) { o->mapper.ba_local_max_refinements++; }},
      {"ba_local_function_tolerance",
       [](auto* o) { o->mapper.ba_local_function_tolerance = 1e-6; }},
      {"repeatable", [](auto* o) { o->repeatable = !o->repeatable; }},
      {"fix_base_in_leaves",
       [](auto* o) { o->fix_base_in_leaves = !o->fix_base_in_leaves; }},
      {"task_ba_global_ratio", [](auto* o) { o->task_ba_global_ratio++; }},
      {"check_kernels", [](auto* o) { o->check_kernels = !o->check_kernels; }},
      {"database_path", [](auto* o) { o->database_path = "/nonexistent"; }},
  };
  const std::vector<Change> later_changes = {
      {"num_threads", [](auto* o) { o->num_threads = 7; }},
      {"output_path", [](auto* o) { o->output_path = "elsewhere"; }},
      {"merge_min_shared_tracks",
       [](auto* o) { o->merge_min_shared_tracks++; }},
      {"refine_merged_models",
       [](auto* o) { o->refine_merged_models = !o->refine_merged_models; }},
      {"complete_models",
       [](auto* o) { o->complete_models = !o->complete_models; }},
      {"keep_work", [](auto* o) { o->keep_work = !o->keep_work; }},
  };
  const fs::path path = WriteTwoImageDatabase();
  TmrMapperOptions defaults;
  defaults.database_path = path.string();
  const std::string tree_json = "{}";
  const std::string base = RunFingerprint(defaults, tree_json);
  EXPECT_NE(RunFingerprint(defaults, "{\"seed\": 1}"), base);
  for (const auto& [name, change] : task_changes) {
    TmrMapperOptions options = defaults;
    change(&options);
    EXPECT_NE(RunFingerprint(options, tree_json), base) << name;
  }
  for (const auto& [name, change] : later_changes) {
    TmrMapperOptions options = defaults;
    change(&options);
    EXPECT_EQ(RunFingerprint(options, tree_json), base) << name;
  }
  fs::remove(path);
}

}  // namespace
}  // namespace tmr
