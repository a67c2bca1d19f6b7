// Copyright (c) 2026, the tmr authors. BSD-3-Clause.
#include "report/report_page.h"

#include <colmap/scene/reconstruction.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "tmr/colmap/synthetic_scene.h"
#include "tmr/colmap/tmr_mapper.h"
#include "tmr/io/atomic_file.h"

namespace tmr {
namespace {

namespace fs = std::filesystem;
using Json = nlohmann::json;

// One run of tmr_mapper on two linked places and one place on its own,
// shared by the tests.
class ReportPageTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    folder_ = new fs::path(fs::temp_directory_path() /
                           ("tmr_report_page_" + std::to_string(getpid())));
    fs::remove_all(*folder_);
    SyntheticSceneOptions scene;
    scene.num_places = 2;
    scene.cameras_per_place = 30;
    scene.num_unlinked_places = 1;
    scene.seed = 3;
    std::string error;
    ASSERT_TRUE(WriteSyntheticScene(scene, Database(), "", nullptr, &error))
        << error;
    TmrMapperOptions options;
    options.database_path = Database();
    options.output_path = Output();
    options.num_threads = 2;
    TmrMapperReport report;
    ASSERT_TRUE(RunTmrMapper(options, &report, &error)) << error;
  }
  static void TearDownTestSuite() {
    fs::remove_all(*folder_);
    delete folder_;
  }
  static std::string Database() { return (*folder_ / "database.db").string(); }
  static std::string Output() { return (*folder_ / "out").string(); }

  static fs::path* folder_;
};

fs::path* ReportPageTest::folder_ = nullptr;

TEST_F(ReportPageTest, DataHoldsTheRunsModelsAndMap) {
  ReportPageOptions options;
  options.max_drawn_points = 1000;
  const std::optional<PartitionMap> map =
      ReadRunPartitionMap(Database(), {}, Output());
  ASSERT_TRUE(map);
  const Json data = Json::parse(ReportPageData(Output(), &*map, options));
  const Json report = Json::parse(
      ReadFileToString((fs::path(Output()) / "report.json").string()));
  EXPECT_EQ(data["run"], report);
  ASSERT_EQ(data["models"].size(), report["model_sizes"].size());
  ASSERT_GE(data["models"].size(), 2u);  // the unlinked place stays apart
  size_t drawn = 0;
  for (size_t m = 0; m < data["models"].size(); ++m) {
    const Json& model = data["models"][m];
    EXPECT_EQ(model["name"], std::to_string(m));
    EXPECT_EQ(model["registered"], report["model_sizes"][m]);
    EXPECT_EQ(model["cameras"].size(), 12 * model["registered"].get<size_t>());
    EXPECT_EQ(model["xyz"].size(), 3 * model["points_drawn"].get<size_t>());
    EXPECT_EQ(model["rgb"].size(), model["xyz"].size());
    drawn += model["points_drawn"].get<size_t>();
  }
  // Shared out by size: at most the budget (plus one per model, rounding).
  EXPECT_LE(drawn, 1000 + data["models"].size());
  EXPECT_GT(drawn, 500u);
  const Json& page_map = data["map"];
  EXPECT_EQ(page_map["names"].size(), map->tree.image_names.size());
  EXPECT_EQ(page_map["xy"].size(), 2 * map->tree.image_names.size());
  EXPECT_EQ(page_map["edges"].size(), 3u * map->similarity.NumEdges());
  EXPECT_EQ(data["kernels"].size(), map->tree.kernels.size());
  EXPECT_TRUE(data["evaluation"].is_null());  // no eval.json yet
}

TEST_F(ReportPageTest, CamerasAreWhereTheModelHasThem) {
  const Json data = Json::parse(ReportPageData(Output(), nullptr, {}));
  EXPECT_TRUE(data["map"].is_null());
  const Json& model = data["models"][0];
  colmap::Reconstruction reconstruction;
  reconstruction.Read((fs::path(Output()) / "0").string());
  // The figures streamed from the files are COLMAP's own.
  EXPECT_EQ(model["registered"], reconstruction.NumRegImages());
  EXPECT_EQ(model["points"], reconstruction.NumPoints3D());
  EXPECT_EQ(model["observations"], reconstruction.ComputeNumObservations());
  EXPECT_NEAR(model["mean_reprojection_error_px"].get<double>(),
              reconstruction.ComputeMeanReprojectionError(), 1e-9);
  std::vector<colmap::image_t> ids = reconstruction.RegImageIds();
  std::sort(ids.begin(), ids.end());
  const double step = model["step"];
  for (size_t i = 0; i < ids.size(); ++i) {
    const Eigen::Vector3d centre =
        reconstruction.Image(ids[i]).ProjectionCenter();
    for (int k = 0; k < 3; ++k) {
      const double decoded = model["origin"][k].get<double>() +
                             step * model["cameras"][12 * i + k].get<double>();
      EXPECT_NEAR(decoded, centre(k), step);
    }
  }
}

TEST(ReportPage, PageHoldsItsDataScriptAndStyleInline) {
  const std::string page =
      ReportPageHtml(R"({"text": "</script><b>/*TMR_SCRIPT*/"})");
  // Every marker filled, the data's text left as it is.
  EXPECT_EQ(page.find("/*TMR_"), page.find("/*TMR_SCRIPT*/\"}"));
  // The data cannot close its script element early.
  EXPECT_NE(page.find(R"({"text": "<\/script><b>/*TMR_SCRIPT*/"})"),
            std::string::npos);
  EXPECT_NE(page.find("tmr-status"), std::string::npos);
  EXPECT_EQ(page.find("http://"), std::string::npos);  // nothing fetched
  EXPECT_EQ(page.find("https://"), std::string::npos);
}

TEST_F(ReportPageTest, RunWritesThePageAndPicture) {
  const fs::path page = fs::path(Output()) / "report.html";
  fs::remove(page);
  std::vector<std::string> lines;
  WriteRunPictures(Database(), {}, Output(),
                   [&lines](const std::string& l) { lines.push_back(l); });
  EXPECT_TRUE(fs::is_regular_file(page));
  EXPECT_TRUE(fs::is_regular_file(fs::path(Output()) / "partition.png"));
  ASSERT_FALSE(lines.empty());
  EXPECT_NE(lines.back().find("report.html written"), std::string::npos);
  // Above the map's limit the page has no map and says so.
  ReportPageOptions no_map;
  no_map.max_map_images = 10;
  lines.clear();
  WriteRunPictures(
      Database(), {}, Output(),
      [&lines](const std::string& l) { lines.push_back(l); }, no_map);
  ASSERT_EQ(lines.size(), 2u);
  EXPECT_NE(lines[0].find("skipped"), std::string::npos);
}

TEST(ReportPage, MissingReportIsAnError) {
  const fs::path empty = fs::temp_directory_path() /
                         ("tmr_report_page_empty_" + std::to_string(getpid()));
  fs::create_directories(empty);
  EXPECT_THROW(ReportPageData(empty.string(), nullptr, {}), std::runtime_error);
  fs::remove_all(empty);
}

}  // namespace
}  // namespace tmr
