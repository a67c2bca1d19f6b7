// Copyright (c) 2026, the tmr authors. BSD-3-Clause.
// The join's adjustment (JoinAdjustment) on a tmr_synth city of two blocks
// cut into two overlapping pieces, as two groups of a merge by parts leave
// it: the second piece placed off by a small rigid motion, the photos both
// hold kept in the first. Adjusted on their longest tracks, tied by the
// keypoints of the shared photos, the pieces come back together.
#include "merge/join_adjustment.h"

#include <colmap/scene/reconstruction.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <unordered_set>

#include "evaluation/evaluate_reconstruction.h"
#include "io/model_files.h"
#include "sfm/model_edits.h"
#include "sfm/test_scene.h"

namespace tmr {
namespace {

namespace fs = std::filesystem;

class JoinAdjustmentTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    std::string error;
    dir_ = WriteTestScene("join_adjustment_test", TwoBlockCity(), &error);
    ASSERT_FALSE(dir_.empty()) << error;
    gt_ = new colmap::Reconstruction(ReadModel((dir_ / "gt").string()));
  }
  static void TearDownTestSuite() {
    delete gt_;
    fs::remove_all(dir_);
  }

  // The ground truth's images `ids` with their tracks cut to them.
  static colmap::Reconstruction Piece(const std::vector<colmap::image_t>& ids) {
    colmap::Reconstruction piece;
    for (const colmap::image_t id : ids)
      AddImageWithoutPoints(*gt_, id, gt_->Image(id).CamFromWorld(), &piece);
    for (const auto& [point_id, point] : gt_->Points3D()) {
      colmap::Track track;
      for (const colmap::TrackElement& element : point.track.Elements())
        if (piece.ExistsImage(element.image_id)) track.AddElement(element);
      if (track.Length() >= 2) piece.AddPoint3D(point.xyz, track);
    }
    return piece;
  }

  // Both pieces written as the join writes them: one copy of each image.
  static colmap::Reconstruction Joined(colmap::Reconstruction first,
                                       const colmap::Reconstruction& second) {
    AppendReconstruction(second, colmap::Sim3d(), &first);
    return first;
  }

  static inline fs::path dir_;
  static inline colmap::Reconstruction* gt_ = nullptr;
};

TEST_F(JoinAdjustmentTest, CompactModelKeepsOnlyTheObservedKeypoints) {
  const CompactTrackModel compact = MakeCompactTrackModel(*gt_, 50);
  EXPECT_EQ(compact.model.NumRegImages(), gt_->NumRegImages());
  EXPECT_LT(compact.model.NumPoints3D(), gt_->NumPoints3D());
  for (const auto& [point_id, point] : compact.model.Points3D()) {
    for (const colmap::TrackElement& element : point.track.Elements()) {
      const colmap::point2D_t original =
          compact.original_index.at(element.image_id).at(element.point2D_idx);
      EXPECT_EQ(
          compact.model.Image(element.image_id).Point2D(element.point2D_idx).xy,
          gt_->Image(element.image_id).Point2D(original).xy);
    }
  }
  for (const colmap::image_t id : compact.model.RegImageIds()) {
    const colmap::Image& image = compact.model.Image(id);
    EXPECT_EQ(image.NumPoints2D(), image.NumPoints3D()) << image.Name();
  }
}

TEST_F(JoinAdjustmentTest, PiecesPlacedOffComeBackTogether) {
  std::vector<colmap::image_t> ids = gt_->RegImageIds();
  std::sort(ids.begin(), ids.end());
  ASSERT_GT(ids.size(), 200u);
  const size_t cut = ids.size() / 2, overlap = ids.size() / 10;
  const std::vector<colmap::image_t> first_ids(ids.begin(),
                                               ids.begin() + cut + overlap);
  const std::vector<colmap::image_t> second_ids(ids.begin() + cut - overlap,
                                                ids.end());
  const std::vector<colmap::image_t> shared(ids.begin() + cut - overlap,
                                            ids.begin() + cut + overlap);
  const colmap::Reconstruction first = Piece(first_ids);
  colmap::Reconstruction second = Piece(second_ids);
  MoveGroupApart(
      std::unordered_set<colmap::image_t>(second_ids.begin(), second_ids.end()),
      colmap::Rigid3d(Eigen::Quaterniond(Eigen::AngleAxisd(
                          0.003, Eigen::Vector3d(0.3, 1.0, 0.2).normalized())),
                      Eigen::Vector3d(0.02, -0.01, 0.015)),
      &second);
  // The join keeps the first piece's copy of the shared images.
  colmap::Reconstruction second_kept = second;
  for (const colmap::image_t id : shared)
    second_kept.DeRegisterFrame(second_kept.Image(id).FrameId());

  JoinAdjustment adjustment;
  adjustment.AddPiece(MakeCompactTrackModel(first, 200), colmap::Sim3d(), {});
  adjustment.AddPiece(MakeCompactTrackModel(second, 200), colmap::Sim3d(),
                      shared);
  EXPECT_GT(adjustment.NumJoinedPoints(), 100u);
  const std::string report =
      adjustment.Adjust(colmap::BundleAdjustmentOptions());
  EXPECT_NE(report.find("CONVERGENCE"), std::string::npos) << report;

  colmap::Reconstruction first_adjusted = first, second_adjusted = second_kept;
  adjustment.MoveToAdjustedPoses(&first_adjusted);
  adjustment.MoveToAdjustedPoses(&second_adjusted);
  const ModelEvaluation before =
      EvaluateReconstruction(*gt_, Joined(first, second_kept), {});
  const ModelEvaluation after =
      EvaluateReconstruction(*gt_, Joined(first_adjusted, second_adjusted), {});
  ASSERT_EQ(after.num_registered_images, static_cast<int>(ids.size()));
  // The same adjustment of the ground truth whole, whose keypoints are
  // noisy: what the pieces can come back to at best.
  JoinAdjustment whole;
  whole.AddPiece(MakeCompactTrackModel(*gt_, 200), colmap::Sim3d(), {});
  whole.Adjust(colmap::BundleAdjustmentOptions());
  colmap::Reconstruction reference = *gt_;
  whole.MoveToAdjustedPoses(&reference);
  const ModelEvaluation best = EvaluateReconstruction(*gt_, reference, {});
  ASSERT_EQ(best.num_registered_images, static_cast<int>(ids.size()));
  EXPECT_GT(before.rotation_error_deg.median, 0.05);
  EXPECT_LT(after.rotation_error_deg.median,
            0.5 * before.rotation_error_deg.median);
  EXPECT_LT(after.rotation_error_deg.median,
            1.5 * best.rotation_error_deg.median)
      << "whole: " << best.rotation_error_deg.median << " deg";
  EXPECT_LT(after.position_error.median, 0.5 * before.position_error.median);
}

}  // namespace
}  // namespace tmr
