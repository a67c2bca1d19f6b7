// Copyright (c) 2026, the tmr authors. BSD-3-Clause.
// The refinement of merged models (RefineMergedModel), by blocks
// (AdjustByBlocks, CovisibleImageBlocks), on a tmr_synth city of two
// blocks whose second half was placed slightly off, its tracks split at the
// seam, as a scene merge leaves it: re-linked and adjusted by blocks of a
// third of the images, the poses come back as well as with the whole model
// adjusted. A small part that joins late is adjusted alone.
#include "merge/merged_model_refinement.h"

#include <colmap/scene/database.h>
#include <colmap/scene/database_cache.h>
#include <colmap/scene/reconstruction.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <iostream>
#include <unordered_set>

#include "evaluation/evaluate_reconstruction.h"
#include "io/model_files.h"
#include "sfm/block_adjustment.h"
#include "sfm/model_edits.h"
#include "sfm/test_scene.h"

namespace tmr {
namespace {

namespace fs = std::filesystem;

class BlockAdjustmentTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    std::string error;
    dir_ = WriteTestScene("block_adjustment_test", TwoBlockCity(), &error);
    ASSERT_FALSE(dir_.empty()) << error;
    cache_ = new std::shared_ptr<colmap::DatabaseCache>(
        LoadTestCache(dir_ / "database.db"));
    gt_ = new colmap::Reconstruction(Matched(
        ReadModel((dir_ / "gt").string()), *(*cache_)->CorrespondenceGraph()));
  }
  static void TearDownTestSuite() {
    delete gt_;
    delete cache_;
    fs::remove_all(dir_);
  }

  // The images of `model` that have matches (COLMAP's mapper takes only
  // those; a photo at a street's end may have none), with the tracks among
  // them.
  static colmap::Reconstruction Matched(
      const colmap::Reconstruction& model,
      const colmap::CorrespondenceGraph& graph) {
    colmap::Reconstruction matched;
    for (const auto& [image_id, image] : model.Images()) {
      if (graph.ExistsImage(image_id))
        AddImageWithoutPoints(model, image_id, image.CamFromWorld(), &matched);
    }
    for (const auto& [point_id, point] : model.Points3D()) {
      colmap::Track track;
      for (const colmap::TrackElement& element : point.track.Elements())
        if (matched.ExistsImage(element.image_id)) track.AddElement(element);
      if (track.Length() >= 2) matched.AddPoint3D(point.xyz, track);
    }
    return matched;
  }

  // The ground truth with the images of the second half of the city (by
  // id) moved by a small rigid motion and their tracks split from the rest.
  static std::shared_ptr<colmap::Reconstruction> MisalignedHalves() {
    auto model = std::make_shared<colmap::Reconstruction>(*gt_);
    std::vector<colmap::image_t> ids = model->RegImageIds();
    std::sort(ids.begin(), ids.end());
    const std::unordered_set<colmap::image_t> half(ids.begin() + ids.size() / 2,
                                                   ids.end());
    const colmap::Rigid3d moved(
        Eigen::Quaterniond(Eigen::AngleAxisd(
            0.003, Eigen::Vector3d(0.3, 1.0, 0.2).normalized())),
        Eigen::Vector3d(0.02, -0.01, 0.015));
    MoveGroupApart(half, moved, model.get());
    return model;
  }

  static inline fs::path dir_;
  static inline colmap::Reconstruction* gt_ = nullptr;
  static inline std::shared_ptr<colmap::DatabaseCache>* cache_ = nullptr;
};

TEST_F(BlockAdjustmentTest, BlocksCoverTheModelOnceAndAreConnected) {
  const size_t num_images = gt_->NumRegImages();
  ASSERT_GT(num_images, 200u);
  const size_t max_images = num_images / 3;
  const auto blocks = CovisibleImageBlocks(*gt_, max_images);
  EXPECT_GE(blocks.size(), 3u);
  std::unordered_set<colmap::image_t> seen;
  for (const auto& block : blocks) {
    EXPECT_LE(block.size(), max_images);
    for (const colmap::image_t id : block)
      EXPECT_TRUE(seen.insert(id).second) << "image " << id << " twice";
    // Every image of the block is reached from its first through points
    // that images of the block share.
    const std::unordered_set<colmap::image_t> inside(block.begin(),
                                                     block.end());
    std::unordered_set<colmap::image_t> reached = {block[0]};
    std::vector<colmap::image_t> queue = {block[0]};
    while (!queue.empty()) {
      const colmap::image_t id = queue.back();
      queue.pop_back();
      for (const colmap::Point2D& point2D : gt_->Image(id).Points2D()) {
        if (!point2D.HasPoint3D()) continue;
        for (const auto& element :
             gt_->Point3D(point2D.point3D_id).track.Elements()) {
          if (inside.count(element.image_id) &&
              reached.insert(element.image_id).second)
            queue.push_back(element.image_id);
        }
      }
    }
    EXPECT_EQ(reached.size(), block.size());
  }
  EXPECT_EQ(seen.size(), num_images);
  EXPECT_THROW(CovisibleImageBlocks(*gt_, 0), std::invalid_argument);
}

TEST_F(BlockAdjustmentTest, BlocksRecoverASeamAsTheWholeAdjustmentDoes) {
  const ModelEvaluation before =
      EvaluateReconstruction(*gt_, *MisalignedHalves(), {});
  // Whole, by blocks, on the longest tracks only (as while scenes merge).
  constexpr int kRuns = 3;
  ModelEvaluation after[kRuns];
  std::string reports[kRuns];
  MergedModelAdjustment adjustments[kRuns];
  adjustments[0].max_block_images = 0;
  adjustments[1].max_block_images = gt_->NumRegImages() / 3;
  adjustments[2].longest_tracks_per_image = 250;
  for (int i = 0; i < kRuns; ++i) {
    const auto model = MisalignedHalves();
    reports[i] =
        RefineMergedModel(*cache_, colmap::IncrementalPipelineOptions(),
                          adjustments[i], model)
            .report;
    after[i] = EvaluateReconstruction(*gt_, *model, {});
    EXPECT_EQ(after[i].num_registered_images, gt_->NumRegImages());
    EXPECT_FALSE(after[i].wrong_merge);
    std::cout << reports[i] << ": median rotation error "
              << after[i].rotation_error_deg.median << " deg ("
              << after[i].centre_aligned_rotation_error_deg.median
              << " after the centres' sim3)\n";
  }
  EXPECT_EQ(reports[0].find("blocks"), std::string::npos) << reports[0];
  EXPECT_NE(reports[1].find("blocks of at most"), std::string::npos)
      << reports[1];
  EXPECT_NE(reports[2].find("global on"), std::string::npos) << reports[2];
  EXPECT_EQ(reports[2].find("blocks"), std::string::npos) << reports[2];
  // The seam is mended and the observations fit as well as with the whole
  // model adjusted. The seam is judged on rotations measured after the sim3
  // fitted to the centres, which sees the shape of the model: measured
  // after a rotation alignment of their own (rotation_error_deg), the two
  // halves turned 0.17 deg apart only show half of it, 0.086 deg.
  const double seam = before.centre_aligned_rotation_error_deg.median;
  EXPECT_LT(after[1].centre_aligned_rotation_error_deg.median, 0.25 * seam);
  EXPECT_LT(after[1].rotation_error_deg.median,
            1.5 * after[0].rotation_error_deg.median + 0.02);
  EXPECT_LT(after[1].mean_reprojection_error_px,
            1.05 * after[0].mean_reprojection_error_px);
  // The longest tracks alone mend the large-scale shape, which is what the
  // merges that follow are tested against.
  EXPECT_LT(after[2].centre_aligned_rotation_error_deg.median, 0.5 * seam);
}

// As a scene merged at once is refined: on its longest tracks, then fully as
// blocks of a quarter of the images side by side. The poses come back as
// well as with the whole model adjusted, and the model does not depend on
// how many blocks ran at once.
TEST_F(BlockAdjustmentTest, BlocksSideBySideDoAsTheWholeAdjustment) {
  MergedModelAdjustment whole;
  whole.max_block_images = 0;
  MergedModelAdjustment longest_tracks;
  longest_tracks.longest_tracks_per_image = 250;
  MergedModelAdjustment blocks = whole;
  blocks.parallel_block_images = gt_->NumRegImages() / 4;
  // One thread per adjustment, as in a repeatable run (Tmr.repeatable).
  colmap::IncrementalPipelineOptions options;
  options.num_threads = 1;
  const auto reference = MisalignedHalves();
  RefineMergedModel(*cache_, options, whole, reference);
  std::shared_ptr<colmap::Reconstruction> models[2];
  for (int workers = 1; workers <= 2; ++workers) {
    auto& model = models[workers - 1];
    model = MisalignedHalves();
    RefineMergedModel(*cache_, options, longest_tracks, model);
    blocks.num_workers = workers;
    const MergedModelRefinement refinement =
        RefineMergedModel(*cache_, options, blocks, model);
    std::cout << workers << " at once: " << refinement.report << "\n";
    EXPECT_NE(refinement.report.find("blocks adjusted at once"),
              std::string::npos)
        << refinement.report;
    EXPECT_GE(refinement.block_seconds.size(), 4u);
    EXPECT_GT(refinement.blocks_wall_seconds, 0);
  }
  for (const colmap::image_t id : models[0]->RegImageIds()) {
    const colmap::Rigid3d a = models[0]->Image(id).CamFromWorld();
    const colmap::Rigid3d b = models[1]->Image(id).CamFromWorld();
    ASSERT_EQ(a.rotation().coeffs(), b.rotation().coeffs()) << id;
    ASSERT_EQ(a.translation(), b.translation()) << id;
  }
  EXPECT_EQ(models[0]->NumPoints3D(), models[1]->NumPoints3D());
  const ModelEvaluation before =
      EvaluateReconstruction(*gt_, *MisalignedHalves(), {});
  const ModelEvaluation by_whole = EvaluateReconstruction(*gt_, *reference, {});
  const ModelEvaluation by_blocks =
      EvaluateReconstruction(*gt_, *models[0], {});
  std::cout << "median rotation error: whole "
            << by_whole.rotation_error_deg.median << " deg, blocks "
            << by_blocks.rotation_error_deg.median << " deg; reprojection "
            << by_whole.mean_reprojection_error_px << " px, "
            << by_blocks.mean_reprojection_error_px << " px\n";
  EXPECT_EQ(by_blocks.num_registered_images, gt_->NumRegImages());
  EXPECT_FALSE(by_blocks.wrong_merge);
  EXPECT_LT(by_blocks.centre_aligned_rotation_error_deg.median,
            0.25 * before.centre_aligned_rotation_error_deg.median);
  EXPECT_LT(by_blocks.rotation_error_deg.median,
            1.5 * by_whole.rotation_error_deg.median + 0.02);
  EXPECT_LT(by_blocks.mean_reprojection_error_px,
            1.05 * by_whole.mean_reprojection_error_px);
}

// A model adjusted whole gets rounds (COLMAP's IterativeGlobalRefinement):
// the split tracks of the seam only fit after the first adjustment, are
// merged then and adjusted again; asked to (the last refinement of a
// scene), the tracks the last round merged and the points it filtered are
// adjusted once more.
TEST_F(BlockAdjustmentTest, RoundsMergeTracksThatFitOnlyAfterAnAdjustment) {
  MergedModelAdjustment one_round;
  one_round.max_block_images = 0;
  MergedModelAdjustment rounds = one_round;
  rounds.max_refinements = 5;
  rounds.adjust_after_last_change = true;
  const auto once = MisalignedHalves();
  const auto repeated = MisalignedHalves();
  const std::string report_once =
      RefineMergedModel(*cache_, colmap::IncrementalPipelineOptions(),
                        one_round, once)
          .report;
  const std::string report =
      RefineMergedModel(*cache_, colmap::IncrementalPipelineOptions(), rounds,
                        repeated)
          .report;
  std::cout << report << "\n";
  EXPECT_EQ(report_once.find("round 2"), std::string::npos) << report_once;
  EXPECT_NE(report.find("round 2"), std::string::npos) << report;
  EXPECT_EQ(report.find("round 6"), std::string::npos) << report;
  EXPECT_EQ(report_once.find("changed observations:"), std::string::npos)
      << report_once;
  EXPECT_NE(report.find("changed observations:"), std::string::npos) << report;
  // More observations in fewer tracks, and poses no worse.
  EXPECT_LT(repeated->NumPoints3D(), once->NumPoints3D());
  const ModelEvaluation a = EvaluateReconstruction(*gt_, *once, {});
  const ModelEvaluation b = EvaluateReconstruction(*gt_, *repeated, {});
  std::cout << "median rotation error: one round "
            << a.rotation_error_deg.median << " deg, rounds "
            << b.rotation_error_deg.median << " deg\n";
  EXPECT_LE(b.rotation_error_deg.median,
            1.05 * a.rotation_error_deg.median + 1e-3);
}

// A small part that joined a model adjusted before (a late scene merge):
// only its images and points are adjusted; every other pose stays as it
// was, and the part comes back onto the model.
TEST_F(BlockAdjustmentTest, ALateJoinAdjustsOnlyTheImagesThatJoined) {
  auto model = std::make_shared<colmap::Reconstruction>(*gt_);
  std::vector<colmap::image_t> ids = model->RegImageIds();
  std::sort(ids.begin(), ids.end());
  const std::vector<colmap::image_t> joined(ids.end() - ids.size() / 10,
                                            ids.end());
  const std::unordered_set<colmap::image_t> group(joined.begin(), joined.end());
  MoveGroupApart(group,
                 colmap::Rigid3d(Eigen::Quaterniond(Eigen::AngleAxisd(
                                     0.003, Eigen::Vector3d::UnitY())),
                                 Eigen::Vector3d(0.02, -0.01, 0.015)),
                 model.get());
  auto rotation_error_deg = [&](colmap::image_t id) {
    return gt_->Image(id).CamFromWorld().rotation().angularDistance(
               model->Image(id).CamFromWorld().rotation()) *
           180.0 / M_PI;
  };
  double before = 0;
  for (const colmap::image_t id : joined) before += rotation_error_deg(id);
  MergedModelAdjustment adjustment;
  adjustment.only_images = joined;
  const std::string report =
      RefineMergedModel(*cache_, colmap::IncrementalPipelineOptions(),
                        adjustment, model)
          .report;
  EXPECT_NE(report.find("block of " + std::to_string(joined.size())),
            std::string::npos)
      << report;
  double after = 0;
  for (const colmap::image_t id : joined) after += rotation_error_deg(id);
  std::cout << report << ": mean rotation error of the part "
            << before / joined.size() << " -> " << after / joined.size()
            << " deg\n";
  EXPECT_LT(after, 0.25 * before);
  for (const colmap::image_t id : ids) {
    if (group.count(id)) continue;
    const colmap::Rigid3d pose = model->Image(id).CamFromWorld();
    const colmap::Rigid3d truth = gt_->Image(id).CamFromWorld();
    // Held: unchanged but for the rotation's normalisation.
    EXPECT_LT(pose.rotation().angularDistance(truth.rotation()), 1e-12) << id;
    EXPECT_LT((pose.translation() - truth.translation()).norm(), 1e-12) << id;
  }
}

}  // namespace
}  // namespace tmr
