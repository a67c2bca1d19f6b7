// Copyright (c) 2026, the tmr authors. BSD-3-Clause.
// tmr_synth's generator: determinism, the scene families' link structure and
// the realism features, checked through COLMAP's and libtmr's readers.
#include <colmap/scene/database.h>
#include <colmap/scene/reconstruction.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <map>
#include <set>

#include "tmr/colmap/synthetic_scene.h"
#include "tmr/io/atomic_file.h"
#include "tmr/io/database_reader.h"
#include "tmr/scene/graph_summary.h"

namespace tmr {
namespace {

namespace fs = std::filesystem;

std::string Part(const std::string& name) {
  return name.substr(0, name.find('/'));
}

class SyntheticSceneTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ =
        fs::temp_directory_path() /
        ("tmr_synth_" +
         std::string(
             ::testing::UnitTest::GetInstance()->current_test_info()->name()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  // Writes a scene into dir_/NAME/{database.db,gt}.
  SyntheticSceneSummary Write(const SyntheticSceneOptions& options,
                              const std::string& name = "scene") {
    SyntheticSceneSummary summary;
    std::string error;
    EXPECT_TRUE(
        WriteSyntheticScene(options, Db(name), Gt(name), &summary, &error))
        << error;
    return summary;
  }
  std::string Db(const std::string& name = "scene") const {
    return (dir_ / name / "database.db").string();
  }
  std::string Gt(const std::string& name = "scene") const {
    return (dir_ / name / "gt").string();
  }

  // Verified pairs between images of the two parts (by name prefix).
  static int PairsBetween(const MatchGraph& graph, const std::string& part1,
                          const std::string& part2) {
    int count = 0;
    for (const MatchGraphPair& pair : graph.pairs) {
      const std::string a = Part(graph.images[pair.image1].name);
      const std::string b = Part(graph.images[pair.image2].name);
      if ((a == part1 && b == part2) || (a == part2 && b == part1)) ++count;
    }
    return count;
  }

  fs::path dir_;
};

SyntheticSceneOptions SmallPlaces() {
  SyntheticSceneOptions options;
  options.cameras_per_place = 30;
  options.place_distance = 100;
  options.false_pairs_per_100_images = 0;
  return options;
}

// On any number of threads too (the pairs' geometries are estimated side by
// side).
TEST_F(SyntheticSceneTest, SameSeedWritesByteIdenticalDatabase) {
  SyntheticSceneOptions options = SmallPlaces();
  options.false_pairs_per_100_images = 2;
  options.seed = 42;
  options.num_threads = 1;
  Write(options, "a");
  options.num_threads = 3;
  Write(options, "b");
  EXPECT_EQ(ReadFileToString(Db("a")), ReadFileToString(Db("b")));
  for (const char* file : {"cameras.bin", "images.bin", "points3D.bin"}) {
    EXPECT_EQ(ReadFileToString(fs::path(Gt("a")) / file),
              ReadFileToString(fs::path(Gt("b")) / file));
  }
  options.seed = 43;
  Write(options, "c");
  EXPECT_NE(ReadFileToString(Db("a")), ReadFileToString(Db("c")));
}

TEST_F(SyntheticSceneTest, PlacesLinkedWeaklyLinkedAndUnlinked) {
  SyntheticSceneOptions options = SmallPlaces();
  options.link_spacing = 3.0;
  Write(options, "strong");
  options.link_spacing = 9.0;
  Write(options, "weak");
  options.link_spacing = 0.0;
  Write(options, "none");

  const MatchGraph strong = ReadMatchGraph(Db("strong"));
  const MatchGraph weak = ReadMatchGraph(Db("weak"));
  const MatchGraph none = ReadMatchGraph(Db("none"));
  // The unlinked place (place2) never pairs with the others.
  for (const MatchGraph* graph : {&strong, &weak, &none}) {
    EXPECT_EQ(PairsBetween(*graph, "place2", "place0"), 0);
    EXPECT_EQ(PairsBetween(*graph, "place2", "place1"), 0);
    EXPECT_EQ(PairsBetween(*graph, "place0", "place1"), 0);
  }
  // A strong link joins place0 and place1 in one component.
  const std::vector<int> labels =
      ConnectedComponents(BuildSimilarityGraph(strong));
  std::set<int> place01, place2;
  for (int i = 0; i < strong.NumImages(); ++i) {
    const std::string part = Part(strong.images[i].name);
    if (part == "place0" || part == "place1") place01.insert(labels[i]);
    if (part == "place2") place2.insert(labels[i]);
  }
  EXPECT_EQ(place01.size(), 1u);
  EXPECT_EQ(place2.size(), 1u);
  EXPECT_NE(*place01.begin(), *place2.begin());
  // The weak link has fewer link images and fewer pairs to the places.
  const int strong_links = PairsBetween(strong, "link0-1", "place0") +
                           PairsBetween(strong, "link0-1", "place1") +
                           PairsBetween(strong, "link0-1", "link0-1");
  const int weak_links = PairsBetween(weak, "link0-1", "place0") +
                         PairsBetween(weak, "link0-1", "place1") +
                         PairsBetween(weak, "link0-1", "link0-1");
  EXPECT_GT(strong_links, 2 * weak_links);
  EXPECT_GT(weak_links, 0);
  EXPECT_EQ(PairsBetween(none, "link0-1", "place0"), 0);
}

TEST_F(SyntheticSceneTest, StreetWithRemovedGapHasNoPairAcrossIt) {
  SyntheticSceneOptions options;
  options.family = "street";
  options.street_length = 200;
  options.street_gap = "removed";
  options.gap_begin = 0.4;
  options.gap_end = 0.7;
  options.false_pairs_per_100_images = 0;
  Write(options);
  colmap::Reconstruction gt;
  gt.ReadBinary(Gt());
  const MatchGraph graph = ReadMatchGraph(Db());
  int across = 0, within = 0;
  for (const MatchGraphPair& pair : graph.pairs) {
    const double x1 =
        gt.Image(graph.images[pair.image1].image_id).ProjectionCenter().x();
    const double x2 =
        gt.Image(graph.images[pair.image2].image_id).ProjectionCenter().x();
    ((x1 < 100) != (x2 < 100) ? across : within)++;
  }
  EXPECT_EQ(across, 0);
  EXPECT_GT(within, 100);

  options.street_gap = "thinned";
  Write(options, "thinned");
  const MatchGraph thinned = ReadMatchGraph(Db("thinned"));
  EXPECT_GT(thinned.NumImages(), graph.NumImages());
  int gap_images = 0;
  for (const auto& image : thinned.images)
    gap_images += Part(image.name) == "gap";
  EXPECT_GT(gap_images, 0);
}

TEST_F(SyntheticSceneTest, RealismFeatures) {
  SyntheticSceneOptions options = SmallPlaces();
  options.false_pairs_per_100_images = 5;
  const SyntheticSceneSummary summary = Write(options);
  EXPECT_GT(summary.num_false_pairs, 0);
  const std::shared_ptr<colmap::Database> database =
      colmap::Database::Open(Db());
  colmap::Reconstruction gt;
  gt.ReadBinary(Gt());
  ASSERT_EQ(database->NumImages(), static_cast<size_t>(summary.num_images));

  std::set<colmap::camera_t> cameras;
  for (const colmap::Image& image : database->ReadAllImages()) {
    cameras.insert(image.CameraId());
    // Every image has its own camera with a prior focal close to the truth.
    const colmap::Camera camera = database->ReadCamera(image.CameraId());
    const colmap::Camera& truth =
        gt.Camera(gt.FindImageWithName(image.Name())->CameraId());
    EXPECT_TRUE(camera.has_prior_focal_length);
    EXPECT_NE(camera.FocalLength(), truth.FocalLength());
    EXPECT_NEAR(camera.FocalLength() / truth.FocalLength(), 1.0, 0.15);
  }
  EXPECT_EQ(cameras.size(), static_cast<size_t>(summary.num_images));

  // Raw matches hold outliers that the verified inliers do not.
  std::vector<std::pair<colmap::image_pair_t, colmap::FeatureMatches>> raw =
      database->ReadAllMatches();
  size_t num_raw = 0, num_inliers = 0;
  for (const auto& [pair_id, matches] : raw) {
    num_raw += matches.size();
    const auto [id1, id2] = colmap::PairIdToImagePair(pair_id);
    num_inliers +=
        database->ReadTwoViewGeometry(id1, id2).inlier_matches.size();
  }
  EXPECT_GT(num_raw, num_inliers * 1.2);

  // Keypoints: unmatched ones exist, the ground truth reprojects within the
  // keypoint noise, and every GT observation is a keypoint of its image.
  const MatchGraph graph = ReadMatchGraph(Db());
  double error_sum = 0;
  size_t num_observations = 0;
  for (const auto& [point_id, point] : gt.Points3D()) {
    for (const colmap::TrackElement& el : point.track.Elements()) {
      const colmap::Image& image = gt.Image(el.image_id);
      const std::optional<Eigen::Vector2d> projected =
          gt.Camera(image.CameraId())
              .ImgFromCam(image.CamFromWorld() * point.xyz);
      ASSERT_TRUE(projected.has_value());
      error_sum += (*projected - image.Point2D(el.point2D_idx).xy).norm();
      ++num_observations;
    }
  }
  ASSERT_GT(num_observations, 1000u);
  const double mean_error = error_sum / num_observations;
  EXPECT_GT(mean_error, 0.3 * options.keypoint_noise_px);
  EXPECT_LT(mean_error, 2.0 * options.keypoint_noise_px);
  for (const MatchGraphImage& image : graph.images) {
    EXPECT_LT(image.num_matched_keypoints, image.num_keypoints) << image.name;
  }
}

TEST_F(SyntheticSceneTest, CityIsOneWellConnectedComponent) {
  SyntheticSceneOptions options;
  options.family = "city";
  options.city_blocks_x = 2;
  options.city_blocks_y = 1;
  options.false_pairs_per_100_images = 0;
  const SyntheticSceneSummary summary = Write(options);
  const MatchGraph graph = ReadMatchGraph(Db());
  const ImageGraph s = BuildSimilarityGraph(graph);
  const GraphSummary stats = SummarizeGraph(graph, s);
  EXPECT_EQ(stats.num_images, summary.num_images);
  EXPECT_GE(stats.component_sizes.front(), 0.98 * summary.num_images);
  EXPECT_GT(stats.mean_degree, 8.0);
}

// Overlapping plazas: one component with no photo left unpaired (ring
// positions inside or behind another plaza's building are drawn again),
// every plaza paired with its grid neighbours, and at detection 0.35 a
// median similarity well below the default scenes' (about 0.09).
TEST_F(SyntheticSceneTest, PlazasOverlapWithoutLinkPhotos) {
  SyntheticSceneOptions options;
  options.family = "plazas";
  options.num_places = 4;
  options.cameras_per_place = 40;
  options.detection_probability = 0.35;
  options.false_pairs_per_100_images = 0;
  const SyntheticSceneSummary summary = Write(options);
  EXPECT_EQ(summary.num_images, 160);
  const MatchGraph graph = ReadMatchGraph(Db());
  const ImageGraph s = BuildSimilarityGraph(graph);
  const GraphSummary stats = SummarizeGraph(graph, s);
  EXPECT_EQ(stats.component_sizes.size(), 1u);
  EXPECT_EQ(stats.num_isolated_images, 0);
  for (const auto& [a, b] :
       {std::pair{"plaza0", "plaza1"}, std::pair{"plaza0", "plaza2"},
        std::pair{"plaza1", "plaza3"}, std::pair{"plaza2", "plaza3"}}) {
    EXPECT_GT(PairsBetween(graph, a, b), 0) << a << " " << b;
  }
  ASSERT_EQ(stats.similarity_quantiles.size(), 5u);
  EXPECT_LT(stats.similarity_quantiles[2], 0.08);
}

TEST_F(SyntheticSceneTest, RejectsBadOptionsAndExistingDatabase) {
  SyntheticSceneOptions options;
  std::string error;
  options.family = "forest";
  EXPECT_FALSE(options.Check(&error));
  EXPECT_NE(error.find("family"), std::string::npos);
  options = SyntheticSceneOptions();
  options.detection_probability = 0;
  EXPECT_FALSE(options.Check());
  options = SyntheticSceneOptions();
  options.gap_begin = 0.8;
  options.gap_end = 0.2;
  EXPECT_FALSE(options.Check());
  options = SyntheticSceneOptions();
  Write(SmallPlaces());
  EXPECT_FALSE(WriteSyntheticScene(options, Db(), "", nullptr, &error));
  EXPECT_NE(error.find("already exists"), std::string::npos);
}

}  // namespace
}  // namespace tmr
