// Copyright (c) 2026, the tmr authors. BSD-3-Clause.
// ReadMatchGraph on databases written by COLMAP's own Database class.
#include <colmap/estimators/two_view_geometry.h>
#include <colmap/scene/database.h>
#include <colmap/scene/reconstruction.h>
#include <colmap/scene/synthetic.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <map>
#include <set>
#include <string>

#include "test_files.h"
#include "tmr/io/database_reader.h"
#include "tmr/scene/image_graph.h"

namespace tmr {
namespace {

namespace fs = std::filesystem;
using colmap::FeatureMatch;
using colmap::FeatureMatches;
using colmap::TwoViewGeometry;

std::set<std::string> ListDirectory(const fs::path& dir) {
  std::set<std::string> names;
  for (const auto& entry : fs::directory_iterator(dir)) {
    names.insert(entry.path().filename().string());
  }
  return names;
}

// Inlier matches (k, offset + k) for k in [first, first + count).
FeatureMatches Diagonal(int first, int count, int offset = 0) {
  FeatureMatches matches;
  for (int k = first; k < first + count; ++k)
    matches.emplace_back(k, k + offset);
  return matches;
}

class MatchGraphColmapTest : public ::testing::Test {
 protected:
  struct Pair {
    colmap::image_t id1, id2;
    FeatureMatches matches;
    TwoViewGeometry::ConfigurationType config;
  };

  void SetUp() override {
    dir_ =
        fs::temp_directory_path() /
        ("tmr_colmap_" +
         std::string(
             ::testing::UnitTest::GetInstance()->current_test_info()->name()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
    path_ = dir_ / "database.db";
  }
  void TearDown() override { fs::remove_all(dir_); }

  // Four images with 50, 60, 70 and 50 keypoints and pairs of every kind the
  // reader has to tell apart.
  void WriteHandMadeDatabase() {
    pairs_ = {
        {1, 2, Diagonal(0, 20), TwoViewGeometry::CALIBRATED},
        {2, 3, Diagonal(10, 16, 5), TwoViewGeometry::UNCALIBRATED},
        {1, 3, Diagonal(30, 14), TwoViewGeometry::CALIBRATED},  // < 15
        {3, 4, Diagonal(40, 30, -40), TwoViewGeometry::WATERMARK},
        {1, 4, Diagonal(0, 25), TwoViewGeometry::DEGENERATE},
        {2, 4, Diagonal(30, 18, -5), TwoViewGeometry::PLANAR},
    };
    const std::shared_ptr<colmap::Database> database =
        colmap::Database::Open(path_.string());
    const colmap::camera_t camera_id =
        database->WriteCamera(colmap::Camera::CreateFromModelName(
            colmap::kInvalidCameraId, "SIMPLE_RADIAL", 500, 640, 480));
    const int num_keypoints[] = {50, 60, 70, 50};
    for (int i = 0; i < 4; ++i) {
      colmap::Image image;
      image.SetName("image" + std::to_string(i + 1) + ".jpg");
      image.SetCameraId(camera_id);
      const colmap::image_t id = database->WriteImage(image);
      ASSERT_EQ(id, static_cast<colmap::image_t>(i + 1));
      database->WriteKeypoints(id, colmap::FeatureKeypoints(num_keypoints[i]));
    }
    for (const Pair& pair : pairs_) {
      TwoViewGeometry geometry;
      geometry.config = pair.config;
      geometry.inlier_matches = pair.matches;
      database->WriteTwoViewGeometry(pair.id1, pair.id2, geometry);
    }
  }

  // n_i by hand: the keypoints of each image in the counted pairs' matches.
  std::map<colmap::image_t, int> MatchedKeypoints(const std::set<int>& configs,
                                                  int min_num_matches) const {
    std::map<colmap::image_t, std::set<int>> used;
    for (const Pair& pair : pairs_) {
      if (!configs.count(pair.config) ||
          static_cast<int>(pair.matches.size()) < min_num_matches) {
        continue;
      }
      for (const FeatureMatch& m : pair.matches) {
        used[pair.id1].insert(m.point2D_idx1);
        used[pair.id2].insert(m.point2D_idx2);
      }
    }
    std::map<colmap::image_t, int> counts;
    for (const auto& [id, set] : used) counts[id] = set.size();
    return counts;
  }

  fs::path dir_;
  fs::path path_;
  std::vector<Pair> pairs_;
};

TEST_F(MatchGraphColmapTest, HandMadeDatabaseGivesJaccardByHand) {
  WriteHandMadeDatabase();
  const MatchGraph graph = ReadMatchGraph(path_.string());
  ASSERT_EQ(graph.NumImages(), 4);
  EXPECT_EQ(graph.images[2].name, "image3.jpg");
  EXPECT_EQ(graph.images[3].num_keypoints, 50);
  // Counted: (1,2) CALIBRATED, (2,3) UNCALIBRATED, (2,4) PLANAR.
  ASSERT_EQ(graph.NumPairs(), 3);
  const std::map<colmap::image_t, int> n =
      MatchedKeypoints({2, 3, 4, 5, 6, 8}, 15);
  // Image 1: 0..19; image 2: 0..19 and 10..25 and 30..47; image 3: 15..30;
  // image 4: 25..42.
  EXPECT_EQ(n.at(1), 20);
  EXPECT_EQ(n.at(2), 26 + 18);
  EXPECT_EQ(n.at(3), 16);
  EXPECT_EQ(n.at(4), 18);
  for (const MatchGraphImage& image : graph.images) {
    EXPECT_EQ(image.num_matched_keypoints, n.at(image.image_id)) << image.name;
  }
  const ImageGraph s = BuildSimilarityGraph(graph);
  const ImageGraph d = BuildDifferenceGraph(s);
  EXPECT_DOUBLE_EQ(s.Weight(0, 1), 20.0 / (20 + 44 - 20));
  EXPECT_DOUBLE_EQ(s.Weight(1, 2), 16.0 / (44 + 16 - 16));
  EXPECT_DOUBLE_EQ(s.Weight(1, 3), 18.0 / (44 + 18 - 18));
  EXPECT_DOUBLE_EQ(s.Weight(0, 2, -1), -1);  // 14 inliers < 15
  EXPECT_DOUBLE_EQ(s.Weight(2, 3, -1), -1);  // watermark
  EXPECT_DOUBLE_EQ(s.Weight(0, 3, -1), -1);  // degenerate
  EXPECT_DOUBLE_EQ(d.Weight(0, 1), 1.0 - 20.0 / 44.0);
}

TEST_F(MatchGraphColmapTest, OptionsChangeWhichPairsCount) {
  WriteHandMadeDatabase();
  MatchGraphOptions options;
  options.min_num_matches = 10;
  options.verified_configs = {2, 3, 4, 5, 6, 7, 8};  // with watermarks
  const MatchGraph graph = ReadMatchGraph(path_.string(), options);
  ASSERT_EQ(graph.NumPairs(), 5);
  const std::map<colmap::image_t, int> n =
      MatchedKeypoints({2, 3, 4, 5, 6, 7, 8}, 10);
  for (const MatchGraphImage& image : graph.images) {
    EXPECT_EQ(image.num_matched_keypoints, n.at(image.image_id)) << image.name;
  }
  const ImageGraph s = BuildSimilarityGraph(graph);
  const double n3 = n.at(3), n4 = n.at(4);
  EXPECT_DOUBLE_EQ(s.Weight(2, 3), 30.0 / (n3 + n4 - 30.0));
}

TEST_F(MatchGraphColmapTest, DatabaseIsByteIdenticalAfterReading) {
  WriteHandMadeDatabase();
  const std::string before = ReadFileToString(path_);
  const std::set<std::string> files_before = ListDirectory(dir_);
  ReadMatchGraph(path_.string());
  EXPECT_EQ(ReadFileToString(path_), before);
  EXPECT_EQ(ListDirectory(dir_), files_before);
}

// While COLMAP still holds the database open, its latest writes sit in the
// -wal file; the reader must see them.
TEST_F(MatchGraphColmapTest, ReadsDatabaseThatColmapHoldsOpen) {
  WriteHandMadeDatabase();
  const std::shared_ptr<colmap::Database> database =
      colmap::Database::Open(path_.string());
  TwoViewGeometry geometry;
  geometry.config = TwoViewGeometry::CALIBRATED;
  geometry.inlier_matches = Diagonal(0, 25);
  database->DeleteTwoViewGeometry(1, 4);  // was DEGENERATE
  database->WriteTwoViewGeometry(1, 4, geometry);
  ASSERT_TRUE(fs::exists(path_.string() + "-wal"));
  const MatchGraph graph = ReadMatchGraph(path_.string());
  EXPECT_EQ(graph.NumPairs(), 4);
  EXPECT_EQ(graph.images[0].num_matched_keypoints, 25);  // 0..24
  EXPECT_EQ(graph.images[3].num_matched_keypoints, 43);  // 0..42
}

TEST_F(MatchGraphColmapTest, ReadsFromReadOnlyFile) {
  WriteHandMadeDatabase();
  fs::permissions(path_, fs::perms::owner_read | fs::perms::group_read);
  EXPECT_EQ(ReadMatchGraph(path_.string()).NumPairs(), 3);
}

// The tables and columns of other COLMAP versions: 3.8 keeps pose priors in
// the images table, 3.12 adds rigs and frames. Only what tmr reads matters.
TEST_F(MatchGraphColmapTest, ReadsColmap38Schema) {
  WriteHandMadeDatabase();
  ExecSql(path_,
          "DROP TABLE pose_priors;"
          "ALTER TABLE images ADD COLUMN prior_qw REAL;"
          "ALTER TABLE images ADD COLUMN prior_qx REAL;"
          "ALTER TABLE images ADD COLUMN prior_qy REAL;"
          "ALTER TABLE images ADD COLUMN prior_qz REAL;"
          "ALTER TABLE images ADD COLUMN prior_tx REAL;"
          "ALTER TABLE images ADD COLUMN prior_ty REAL;"
          "ALTER TABLE images ADD COLUMN prior_tz REAL;"
          "PRAGMA user_version = 3800;");
  EXPECT_EQ(ReadMatchGraph(path_.string()).NumPairs(), 3);
}

// COLMAP 4's schema with a rig and a frame (the tables 3.12 introduced),
// and a pair verified by COLMAP 4's rig verification (CALIBRATED_RIG),
// which counts as COLMAP's mapper counts it.
TEST_F(MatchGraphColmapTest, ReadsRigsAndFrames) {
  WriteHandMadeDatabase();
  ExecSql(path_,
          "INSERT INTO rigs VALUES(1, 1, 0);"
          "INSERT INTO frames VALUES(1, 1);"
          "INSERT INTO frame_data VALUES(1, 1, 1, 0);"
          "UPDATE two_view_geometries SET config = 9 "
          "  WHERE pair_id = 2147483647 * 1 + 2;");
  const MatchGraph graph = ReadMatchGraph(path_.string());
  ASSERT_EQ(graph.NumPairs(), 3);
  EXPECT_EQ(graph.pairs[0].config, 9);
}

// SynthesizeDataset writes exhaustive matches between all observations of
// each 3D point; n_i and n_ij must agree with COLMAP's own reading of them.
TEST_F(MatchGraphColmapTest, SynthesizedDatasetAgreesWithColmapReader) {
  {
    const std::shared_ptr<colmap::Database> database =
        colmap::Database::Open(path_.string());
    colmap::SyntheticDatasetOptions options;
    options.num_rigs = 3;
    options.num_cameras_per_rig = 1;
    options.num_frames_per_rig = 4;
    options.num_points3D = 300;
    options.num_points2D_without_point3D = 40;
    colmap::Reconstruction reconstruction;
    colmap::SynthesizeDataset(options, &reconstruction, database.get());
  }
  const MatchGraph graph = ReadMatchGraph(path_.string());
  ASSERT_EQ(graph.NumImages(), 12);

  const std::shared_ptr<colmap::Database> database =
      colmap::Database::Open(path_.string());
  std::map<colmap::image_t, std::set<colmap::point2D_t>> used;
  std::map<std::pair<int, int>, int> inliers;
  for (const auto& [pair_id, geometry] : database->ReadTwoViewGeometries()) {
    if (geometry.inlier_matches.size() < 15) continue;
    const auto [id1, id2] = colmap::PairIdToImagePair(pair_id);
    for (const FeatureMatch& m : geometry.inlier_matches) {
      used[id1].insert(m.point2D_idx1);
      used[id2].insert(m.point2D_idx2);
    }
    inliers[{graph.FindImageIndex(id1), graph.FindImageIndex(id2)}] =
        geometry.inlier_matches.size();
  }
  ASSERT_EQ(graph.NumPairs(), static_cast<int>(inliers.size()));
  for (const MatchGraphPair& pair : graph.pairs) {
    EXPECT_EQ(pair.num_inliers, inliers.at({pair.image1, pair.image2}));
  }
  for (const MatchGraphImage& image : graph.images) {
    EXPECT_EQ(image.num_keypoints,
              static_cast<int>(database->NumKeypointsForImage(image.image_id)));
    EXPECT_EQ(image.num_matched_keypoints,
              static_cast<int>(used[image.image_id].size()));
    EXPECT_LT(image.num_matched_keypoints, image.num_keypoints);
  }
  const ImageGraph s = BuildSimilarityGraph(graph);
  for (const WeightedEdge& e : s.Edges()) {
    EXPECT_GT(e.weight, 0.0);
    EXPECT_LE(e.weight, 1.0);
  }
}

class CorruptDatabaseTest : public MatchGraphColmapTest {
 protected:
  void ExpectError(const std::string& sql, const std::string& problem) {
    WriteHandMadeDatabase();
    ExecSql(path_, sql);
    const std::string before = ReadFileToString(path_);
    try {
      ReadMatchGraph(path_.string());
      FAIL() << "no error after " << sql;
    } catch (const DatabaseError& e) {
      const std::string message = e.what();
      EXPECT_NE(message.find(path_.string()), std::string::npos) << message;
      EXPECT_NE(message.find(problem), std::string::npos) << message;
    }
    EXPECT_EQ(ReadFileToString(path_), before);
  }
  // pair_id of images 1 and 2.
  static constexpr int64_t kPair12 = 2147483647LL + 2;
};

TEST_F(CorruptDatabaseTest, BlobShorterThanRowsTimesCols) {
  ExpectError(
      "UPDATE two_view_geometries SET data = substr(data, 1, 100) "
      "WHERE pair_id = " +
          std::to_string(kPair12),
      "data blob of 100 bytes, expected rows x cols x 4 = 160");
}

TEST_F(CorruptDatabaseTest, RowsLargerThanBlob) {
  ExpectError("UPDATE two_view_geometries SET rows = 21 WHERE pair_id = " +
                  std::to_string(kPair12),
              "expected rows x cols x 4 = 168");
}

TEST_F(CorruptDatabaseTest, WrongColumnCount) {
  ExpectError("UPDATE two_view_geometries SET cols = 3 WHERE pair_id = " +
                  std::to_string(kPair12),
              "20 x 3 inlier matches");
}

TEST_F(CorruptDatabaseTest, PairNamesUnknownImage) {
  ExpectError(
      "UPDATE two_view_geometries SET pair_id = 2147483647 * 1 + 9 "
      "WHERE pair_id = " +
          std::to_string(kPair12),
      "names image_id 1 and 9");
}

TEST_F(CorruptDatabaseTest, MatchBeyondKeypoints) {
  ExpectError("UPDATE keypoints SET rows = 10 WHERE image_id = 1",
              "matches keypoint 10 of image_id 1 (10 keypoints)");
}

TEST_F(CorruptDatabaseTest, MissingTable) {
  ExpectError("DROP TABLE two_view_geometries",
              "has no table 'two_view_geometries'");
}

}  // namespace
}  // namespace tmr
