// Copyright (c) 2026, the tmr authors. BSD-3-Clause.
#include "controllers/task_workspace.h"

#include <colmap/scene/database.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <string>
#include <type_traits>
#include <variant>

#include "tmr/io/atomic_file.h"

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

// Sets the row's field to another value.
void ChangeValue(const OptionRow& row) {
  std::visit(
      [](auto* field) {
        using T = std::decay_t<decltype(*field)>;
        if constexpr (std::is_same_v<T, bool>)
          *field = !*field;
        else if constexpr (std::is_same_v<T, std::string>)
          *field += "x";
        else if constexpr (std::is_same_v<T, double>)
          *field = *field * 1.5 + 0.25;
        else
          *field += 1;
      },
      row.value);
}

// Every option that reaches a kernel or leaf task must change the
// fingerprint, or a rerun with another value reuses tasks made with the old
// one; the options of later stages must not (a rerun reuses the tasks). The
// partition's options reach it through tree.json.
TEST(RunFingerprint, ChangesWithEveryOptionThatReachesATask) {
  const fs::path path = WriteTwoImageDatabase();
  TmrMapperOptions defaults;
  defaults.database_path = path.string();
  const std::string tree_json = "{}";
  const std::string base = RunFingerprint(defaults, tree_json);
  EXPECT_NE(RunFingerprint(defaults, "{\"Tmr.seed\": 1}"), base);
  TmrMapperOptions other_database = defaults;
  other_database.database_path = "/nonexistent";
  EXPECT_NE(RunFingerprint(other_database, tree_json), base);

  OptionTable rows;
  defaults.AddTo(&rows);
  int num_task_rows = 0;
  for (size_t i = 0; i < rows.rows().size(); ++i) {
    TmrMapperOptions options = defaults;
    OptionTable table;
    options.AddTo(&table);
    const OptionRow& row = table.rows()[i];
    ChangeValue(row);
    if (row.changes_tasks) {
      ++num_task_rows;
      EXPECT_NE(RunFingerprint(options, tree_json), base) << row.name;
    } else {
      EXPECT_EQ(RunFingerprint(options, tree_json), base) << row.name;
    }
    // The mapper's options and these four reach the tasks.
    const bool reaches_tasks = (row.name.rfind("Mapper.", 0) == 0 &&
                                row.name != "Mapper.num_threads") ||
                               row.name == "Tmr.repeatable" ||
                               row.name == "Tmr.fix_base_in_leaves" ||
                               row.name == "Tmr.task_ba_global_ratio" ||
                               row.name == "Tmr.check_kernels";
    EXPECT_EQ(row.changes_tasks, reaches_tasks) << row.name;
  }
  EXPECT_EQ(num_task_rows, 24);
  fs::remove(path);
}

}  // namespace
}  // namespace tmr
