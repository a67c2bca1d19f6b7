// Copyright (c) 2026, the tmr authors. BSD-3-Clause.
// RefineModel on a tmr_synth place: its ground truth refined from files is
// written back with every image, at sub-pixel reprojection error; a missing
// model or impossible options give a reason, not a crash.
#include "tmr/colmap/model_refinement.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "io/model_files.h"
#include "sfm/test_scene.h"

namespace tmr {
namespace {

namespace fs = std::filesystem;

TEST(RefineModel, RefinesAModelFromFiles) {
  SyntheticSceneOptions scene;
  scene.num_places = 1;
  scene.num_unlinked_places = 0;
  scene.cameras_per_place = 20;
  std::string error;
  const fs::path dir = WriteTestScene("refine_model_test", scene, &error);
  ASSERT_FALSE(dir.empty()) << error;
  const colmap::Reconstruction gt = ReadModel((dir / "gt").string());
  const std::string database = (dir / "database.db").string();
  const auto before = fs::last_write_time(database);

  ModelRefinementOptions options;
  ModelRefinementReport report;
  ASSERT_TRUE(RefineModel(database, (dir / "gt").string(),
                          (dir / "refined").string(), dir.string(), options,
                          &report, &error))
      << error;
  EXPECT_EQ(report.num_images, static_cast<int>(gt.NumRegImages()));
  EXPECT_LT(report.mean_reprojection_error_px, 1.0);
  EXPECT_FALSE(report.message.empty());
  const colmap::Reconstruction refined = ReadModel((dir / "refined").string());
  EXPECT_EQ(refined.NumRegImages(), gt.NumRegImages());
  EXPECT_EQ(fs::last_write_time(database), before);

  EXPECT_FALSE(RefineModel(database, (dir / "no_model").string(), "",
                           dir.string(), options, &report, &error));
  EXPECT_NE(error.find("no_model"), std::string::npos) << error;
  options.num_threads = 0;
  EXPECT_FALSE(RefineModel(database, (dir / "gt").string(), "", dir.string(),
                           options, &report, &error));
  EXPECT_NE(error.find("num_threads"), std::string::npos) << error;
  fs::remove_all(dir);
}

}  // namespace
}  // namespace tmr
