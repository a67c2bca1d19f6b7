// Copyright (c) 2026, the tmr authors. BSD-3-Clause.
// The databases users bring: the same photos in COLMAP
// 3.8's schema (written by SQL here, with the zero matrices and identity
// relative poses 3.x wrote where nothing was estimated) and in a COLMAP 4
// database in WAL mode whose latest writes sit only in its -wal file give
// the partition and the models of the COLMAP 4.1 database they were made
// from, image by image; a database with real multi-camera rigs (COLMAP's
// own synthetic dataset) is mapped with its images as independent cameras
// and says so. Every input is byte-identical afterwards.
#include <colmap/scene/database.h>
#include <colmap/scene/reconstruction.h>
#include <colmap/scene/synthetic.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

#include "test_files.h"
#include "tmr/colmap/synthetic_scene.h"
#include "tmr/colmap/tmr_mapper.h"
#include "tmr/io/database_reader.h"
#include "tmr/partition/tmr_tree.h"

namespace tmr {
namespace {

namespace fs = std::filesystem;

// COLMAP 3.8's tables (src/base/database.cc of 3.8): pose priors in the
// images table, no rigs, frames or pose_priors, descriptors without a type.
constexpr char kColmap38Schema[] = R"sql(
CREATE TABLE cameras (camera_id INTEGER PRIMARY KEY AUTOINCREMENT NOT NULL,
  model INTEGER NOT NULL, width INTEGER NOT NULL, height INTEGER NOT NULL,
  params BLOB, prior_focal_length INTEGER NOT NULL);
CREATE TABLE images (image_id INTEGER PRIMARY KEY AUTOINCREMENT NOT NULL,
  name TEXT NOT NULL UNIQUE, camera_id INTEGER NOT NULL, prior_qw REAL,
  prior_qx REAL, prior_qy REAL, prior_qz REAL, prior_tx REAL, prior_ty REAL,
  prior_tz REAL,
  CONSTRAINT image_id_check CHECK(image_id >= 0 and image_id < 2147483647),
  FOREIGN KEY(camera_id) REFERENCES cameras(camera_id));
CREATE UNIQUE INDEX index_name ON images(name);
CREATE TABLE keypoints (image_id INTEGER PRIMARY KEY NOT NULL,
  rows INTEGER NOT NULL, cols INTEGER NOT NULL, data BLOB,
  FOREIGN KEY(image_id) REFERENCES images(image_id) ON DELETE CASCADE);
CREATE TABLE descriptors (image_id INTEGER PRIMARY KEY NOT NULL,
  rows INTEGER NOT NULL, cols INTEGER NOT NULL, data BLOB,
  FOREIGN KEY(image_id) REFERENCES images(image_id) ON DELETE CASCADE);
CREATE TABLE matches (pair_id INTEGER PRIMARY KEY NOT NULL,
  rows INTEGER NOT NULL, cols INTEGER NOT NULL, data BLOB);
CREATE TABLE two_view_geometries (pair_id INTEGER PRIMARY KEY NOT NULL,
  rows INTEGER NOT NULL, cols INTEGER NOT NULL, data BLOB,
  config INTEGER NOT NULL, F BLOB, E BLOB, H BLOB, qvec BLOB, tvec BLOB);
PRAGMA user_version = 3800;
)sql";

// The rows of the COLMAP 4 database attached as `v4`, as 3.8 stored them:
// zeros for matrices that were not estimated, an identity relative pose.
constexpr char kCopyAs38[] = R"sql(
INSERT INTO cameras SELECT camera_id, model, width, height, params,
  prior_focal_length FROM v4.cameras;
INSERT INTO images(image_id, name, camera_id)
  SELECT image_id, name, camera_id FROM v4.images;
INSERT INTO keypoints SELECT image_id, rows, cols, data FROM v4.keypoints;
INSERT INTO descriptors SELECT image_id, rows, cols, data FROM v4.descriptors;
INSERT INTO matches SELECT pair_id, rows, cols, data FROM v4.matches;
INSERT INTO two_view_geometries SELECT pair_id, rows, cols, data, config,
  IFNULL(F, zeroblob(72)), IFNULL(E, zeroblob(72)), IFNULL(H, zeroblob(72)),
  IFNULL(qvec, X'000000000000F03F' || zeroblob(24)), IFNULL(tvec, zeroblob(24))
  FROM v4.two_view_geometries;
)sql";

class DatabaseSchemasTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    SyntheticSceneOptions options;
    options.num_places = 2;
    options.cameras_per_place = 30;
    options.num_unlinked_places = 0;
    options.seed = 5;
    // A folder of this process's own: ctest runs each test case as a
    // process, side by side.
    scene_ = new fs::path(fs::temp_directory_path() /
                          ("tmr_schemas_" + std::to_string(getpid())));
    fs::remove_all(*scene_);
    std::string error;
    ASSERT_TRUE(WriteSyntheticScene(options, (*scene_ / "database.db").string(),
                                    (*scene_ / "gt").string(), nullptr,
                                    &error))
        << error;
  }
  static void TearDownTestSuite() {
    fs::remove_all(*scene_);
    delete scene_;
  }
  static fs::path Colmap4Database() { return *scene_ / "database.db"; }

  // The TMR-tree of a database, as tree.json holds it (without timings).
  static std::string PartitionJson(const fs::path& database) {
    TmrTree tree = BuildTmrTree(ReadMatchGraph(database.string()), {});
    tree.timing = {};
    std::ostringstream json;
    WriteTmrTreeJson(tree, json);
    return json.str();
  }

  // tmr_mapper on a database into `output`; the progress lines.
  static std::vector<std::string> Map(const fs::path& database,
                                      const fs::path& output) {
    TmrMapperOptions options;
    options.database_path = database.string();
    options.output_path = output.string();
    options.num_threads = 2;
    std::vector<std::string> lines;
    TmrMapperReport report;
    std::string error;
    EXPECT_TRUE(RunTmrMapper(
        options, &report, &error,
        [&lines](const std::string& line) { lines.push_back(line); }))
        << error;
    return lines;
  }

  // The models in two output folders hold the same images with the same
  // poses and the same number of points.
  static void ExpectSameModels(const fs::path& expected,
                               const fs::path& actual) {
    int k = 0;
    for (; fs::exists(expected / std::to_string(k)); ++k) {
      SCOPED_TRACE("model " + std::to_string(k));
      ASSERT_TRUE(fs::exists(actual / std::to_string(k)));
      colmap::Reconstruction a, b;
      a.ReadBinary(expected / std::to_string(k));
      b.ReadBinary(actual / std::to_string(k));
      ASSERT_EQ(a.NumRegImages(), b.NumRegImages());
      EXPECT_EQ(a.NumPoints3D(), b.NumPoints3D());
      for (const colmap::image_t id : a.RegImageIds()) {
        ASSERT_TRUE(b.ExistsImage(id) && b.Image(id).HasPose()) << id;
        EXPECT_EQ(a.Image(id).CamFromWorld().ToMatrix(),
                  b.Image(id).CamFromWorld().ToMatrix())
            << "image " << id;
      }
    }
    EXPECT_GT(k, 0);
    EXPECT_FALSE(fs::exists(actual / std::to_string(k)));
  }

  static fs::path* scene_;
};

fs::path* DatabaseSchemasTest::scene_ = nullptr;

TEST_F(DatabaseSchemasTest, Colmap38SchemaGivesTheSamePartitionAndModels) {
  const fs::path v38 = *scene_ / "colmap38.db";
  fs::remove(v38);
  ExecSql(v38, std::string(kColmap38Schema) + "ATTACH DATABASE '" +
                   ReadOnlySqliteUri(Colmap4Database().string()) + "' AS v4;" +
                   kCopyAs38 + "DETACH DATABASE v4;");
  const std::string bytes = ReadFileToString(v38);

  EXPECT_EQ(PartitionJson(v38), PartitionJson(Colmap4Database()));
  Map(Colmap4Database(), *scene_ / "out_v4");
  Map(v38, *scene_ / "out_v38");
  ExpectSameModels(*scene_ / "out_v4", *scene_ / "out_v38");
  EXPECT_EQ(ReadFileToString(v38), bytes);
}

// A COLMAP 4 database left in WAL mode with its verified pairs only in the
// -wal file (a process that wrote them was killed before a checkpoint):
// tmr reads through the WAL and changes neither file.
TEST_F(DatabaseSchemasTest, WalDatabaseWithPendingWritesIsReadThroughTheWal) {
  const fs::path writer = *scene_ / "wal_writer";
  const fs::path copy = *scene_ / "wal";
  fs::create_directories(writer);
  fs::create_directories(copy);
  fs::copy_file(Colmap4Database(), writer / "database.db",
                fs::copy_options::overwrite_existing);
  ExecSql(writer / "database.db",
          "PRAGMA journal_mode = WAL; DELETE FROM two_view_geometries;"
          "PRAGMA wal_checkpoint(TRUNCATE);");
  std::unique_ptr<SqliteDatabase> open =
      ExecSql(writer / "database.db",
              "PRAGMA wal_autocheckpoint = 0; ATTACH DATABASE '" +
                  ReadOnlySqliteUri(Colmap4Database().string()) +
                  "' AS v4; INSERT INTO two_view_geometries SELECT * FROM "
                  "v4.two_view_geometries; DETACH DATABASE v4;");
  // The files as a crash would leave them: copied while still open.
  fs::copy_file(writer / "database.db", copy / "database.db",
                fs::copy_options::overwrite_existing);
  fs::copy_file(writer / "database.db-wal", copy / "database.db-wal",
                fs::copy_options::overwrite_existing);
  open.reset();
  const fs::path wal_db = copy / "database.db";
  const std::string bytes = ReadFileToString(wal_db);
  const std::string wal_bytes = ReadFileToString(copy / "database.db-wal");
  ASSERT_GT(wal_bytes.size(), 0u);

  EXPECT_EQ(PartitionJson(wal_db), PartitionJson(Colmap4Database()));
  Map(Colmap4Database(), *scene_ / "out_v4_for_wal");
  Map(wal_db, *scene_ / "out_wal");
  ExpectSameModels(*scene_ / "out_v4_for_wal", *scene_ / "out_wal");
  EXPECT_EQ(ReadFileToString(wal_db), bytes);
  EXPECT_EQ(ReadFileToString(copy / "database.db-wal"), wal_bytes);
}

// COLMAP's synthetic dataset with two rigs of two cameras each: tmr says in
// one progress line that it maps the rigs' images as independent cameras,
// and registers them.
TEST_F(DatabaseSchemasTest, MultiCameraRigsAreMappedAsIndependentCameras) {
  const fs::path dir = *scene_ / "rigs";
  fs::create_directories(dir);
  const fs::path database = dir / "database.db";
  fs::remove(database);
  {
    const std::shared_ptr<colmap::Database> db =
        colmap::Database::Open(database.string());
    colmap::SyntheticDatasetOptions options;
    options.num_rigs = 2;
    options.num_cameras_per_rig = 2;
    options.num_frames_per_rig = 12;
    options.num_points3D = 400;
    colmap::Reconstruction truth;
    colmap::SynthesizeDataset(options, &truth, db.get());
    ASSERT_EQ(db->NumRigs(), 2u);
  }
  const std::string bytes = ReadFileToString(database);
  const std::vector<std::string> lines = Map(database, dir / "out");
  int rig_lines = 0;
  for (const std::string& line : lines) {
    rig_lines += line.find("2 rig(s) of several cameras") != std::string::npos;
  }
  EXPECT_EQ(rig_lines, 1);
  colmap::Reconstruction model;
  model.ReadBinary(dir / "out" / "0");
  EXPECT_GE(model.NumRegImages(), 44u);  // of 48
  EXPECT_EQ(ReadFileToString(database), bytes);
}

}  // namespace
}  // namespace tmr
