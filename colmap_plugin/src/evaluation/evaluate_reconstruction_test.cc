// Copyright (c) 2026, the tmr authors. BSD-3-Clause.
// tmr_eval's scoring on ground truth, on a similarity-transformed copy and on
// a copy with one part displaced (a wrong merge), and on noisy centres.
#include <colmap/geometry/sim3.h>
#include <colmap/math/math.h>
#include <colmap/scene/reconstruction.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <random>
#include <sstream>

#include "evaluation/evaluate_reconstruction.h"
#include "io/model_files.h"
#include "sfm/model_edits.h"
#include "sfm/test_scene.h"

namespace tmr {
namespace {

namespace fs = std::filesystem;

class ModelEvaluationTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    SyntheticSceneOptions options;
    options.cameras_per_place = 30;
    options.num_unlinked_places = 0;
    options.place_distance = 100;
    std::string error;
    dir_ = WriteTestScene("model_evaluation_test", options, &error);
    ASSERT_FALSE(dir_.empty()) << error;
    gt_ = new colmap::Reconstruction(ReadModel((dir_ / "gt").string()));
  }
  static void TearDownTestSuite() {
    delete gt_;
    fs::remove_all(dir_);
  }

  static fs::path dir_;
  static colmap::Reconstruction* gt_;
};

fs::path ModelEvaluationTest::dir_;
colmap::Reconstruction* ModelEvaluationTest::gt_ = nullptr;

TEST_F(ModelEvaluationTest, GroundTruthAgainstItselfHasZeroError) {
  const ModelEvaluation e = EvaluateReconstruction(*gt_, *gt_, {});
  EXPECT_TRUE(e.aligned);
  EXPECT_EQ(e.num_common_images, static_cast<int>(gt_->NumRegImages()));
  EXPECT_EQ(e.num_alignment_inliers, e.num_common_images);
  EXPECT_LT(e.rotation_error_deg.max, 1e-6);
  EXPECT_LT(e.position_error.max, 1e-9);
  EXPECT_FALSE(e.wrong_merge);
  EXPECT_GT(e.scene_scale, 10.0);
}

TEST_F(ModelEvaluationTest, SimilarityTransformedCopyHasZeroError) {
  colmap::Reconstruction copy = *gt_;
  copy.Transform(colmap::Sim3d(0.37,
                               Eigen::Quaterniond(Eigen::AngleAxisd(
                                   1.1, Eigen::Vector3d(1, 2, 3).normalized())),
                               Eigen::Vector3d(100, -50, 7)));
  const ModelEvaluation e = EvaluateReconstruction(*gt_, copy, {});
  EXPECT_TRUE(e.aligned);
  EXPECT_LT(e.rotation_error_deg.max, 1e-6);
  EXPECT_LT(e.position_error.max, 1e-6);
  EXPECT_FALSE(e.wrong_merge);
  EXPECT_EQ(e.num_points3D, static_cast<int>(gt_->NumPoints3D()));
}

TEST_F(ModelEvaluationTest, DisplacedPartIsAWrongMerge) {
  // Move place1 (30 images) 25 m sideways and turn it by 20 degrees.
  colmap::Reconstruction copy = *gt_;
  const Eigen::Vector3d shift(0, 25, 0);
  const Eigen::Quaterniond turn(
      Eigen::AngleAxisd(0.349, Eigen::Vector3d::UnitZ()));
  int moved = 0;
  for (const colmap::image_t id : copy.RegImageIds()) {
    const colmap::Image& image = copy.Image(id);
    if (image.Name().rfind("place1/", 0) != 0) continue;
    // New world-from-camera: turn about the origin, then shift.
    const colmap::Rigid3d world_from_cam =
        colmap::Inverse(image.CamFromWorld());
    const colmap::Rigid3d moved_pose(
        turn * world_from_cam.rotation(),
        turn * world_from_cam.translation() + shift);
    SetPoseAndRegister(id, colmap::Inverse(moved_pose), &copy);
    ++moved;
  }
  ASSERT_EQ(moved, 30);
  const ModelEvaluation e = EvaluateReconstruction(*gt_, copy, {});
  EXPECT_TRUE(e.aligned);
  EXPECT_TRUE(e.wrong_merge);
  EXPECT_EQ(e.num_displaced_images, 30);
  EXPECT_NEAR(e.displacement_rotation_deg, 20.0, 0.5);
  // Place1 lies about 100 m from the origin: the part moves by more than
  // the shift alone. The reported displacement is relative to the scale.
  EXPECT_GT(e.displacement * e.scene_scale, 25.0);
  std::ostringstream table;
  PrintEvaluationTable({e}, table);
  EXPECT_NE(table.str().find("YES: 30 images displaced"), std::string::npos)
      << table.str();
  std::ostringstream json;
  WriteEvaluationJson({e}, "gt", json);
  EXPECT_NE(json.str().find("\"wrong_merge\": true"), std::string::npos);
}

TEST_F(ModelEvaluationTest, RotationErrorsDoNotDependOnCentreNoise) {
  // Orientations exact but for one image turned by 1 degree about its
  // centre; every centre moved by noise of about 0.5% of the scene scale.
  colmap::Reconstruction copy = *gt_;
  std::mt19937 random(7);
  std::normal_distribution<double> noise(0.0, 0.5);
  colmap::image_t turned = colmap::kInvalidImageId;
  for (const colmap::image_t id : copy.RegImageIds()) {
    const colmap::Rigid3d world_from_cam =
        colmap::Inverse(copy.Image(id).CamFromWorld());
    Eigen::Quaterniond rotation = world_from_cam.rotation();
    if (turned == colmap::kInvalidImageId) {
      turned = id;
      rotation =
          rotation * Eigen::Quaterniond(Eigen::AngleAxisd(
                         colmap::DegToRad(1.0), Eigen::Vector3d::UnitY()));
    }
    const Eigen::Vector3d centre =
        world_from_cam.translation() +
        Eigen::Vector3d(noise(random), noise(random), noise(random));
    SetPoseAndRegister(id, colmap::Inverse(colmap::Rigid3d(rotation, centre)),
                       &copy);
  }
  const ModelEvaluation e = EvaluateReconstruction(*gt_, copy, {});
  ASSERT_TRUE(e.aligned);
  EXPECT_LT(e.rotation_error_deg.median, 1e-6);
  EXPECT_NEAR(e.rotation_error_deg.max, 1.0, 1e-6);
  // The sim3 fitted to the noisy centres turns every orientation a little.
  EXPECT_GT(e.centre_aligned_rotation_error_deg.median, 1e-3);
  std::ostringstream json;
  WriteEvaluationJson({e}, "gt", json);
  EXPECT_NE(json.str().find("\"centre_aligned_rotation_error_deg\""),
            std::string::npos);
}

TEST_F(ModelEvaluationTest, PartialModelIsScoredOnCommonImages) {
  colmap::Reconstruction part = *gt_;
  std::vector<colmap::image_t> drop;
  for (const colmap::image_t id : part.RegImageIds()) {
    if (part.Image(id).Name().rfind("place0/", 0) != 0) drop.push_back(id);
  }
  for (const colmap::image_t id : drop)
    part.DeRegisterFrame(part.Image(id).FrameId());
  const ModelEvaluation e = EvaluateReconstruction(*gt_, part, {});
  EXPECT_EQ(e.num_registered_images, 30);
  EXPECT_EQ(e.num_common_images, 30);
  EXPECT_LT(e.position_error.max, 1e-9);
}

TEST(ModelEvaluationOptions, Check) {
  ModelEvaluationOptions options;
  EXPECT_TRUE(options.Check());
  options.displaced_threshold = options.inlier_threshold / 2;
  EXPECT_FALSE(options.Check());
  EXPECT_THROW(ReadModel("/nonexistent/model"), std::runtime_error);
}

// With a database, the model is checked against its verified matches
// (CheckMatchConsistency); the database is left as it was.
TEST_F(ModelEvaluationTest, TheMatchConsistencyCheckIsReported) {
  const std::string database = (dir_ / "database.db").string();
  ModelEvaluationOptions options;
  options.database_path = database;
  const auto before = fs::last_write_time(database);
  const ModelEvaluation e = EvaluateModel("", (dir_ / "gt").string(), options);
  ASSERT_TRUE(e.match_consistency.has_value());
  EXPECT_TRUE(e.match_consistency->IsConsistent(MatchConsistencyOptions()));
  EXPECT_TRUE(e.match_consistent);
  EXPECT_GT(e.match_consistency->num_matches, 10000);
  EXPECT_EQ(fs::last_write_time(database), before);
}

}  // namespace
}  // namespace tmr
