// Copyright (c) 2026, the tmr authors. BSD-3-Clause.
// The cluster merge (MergeLeafModels) on models cut from a tmr_synth
// place.
#include "merge/cluster_merge.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <vector>

#include "merge/merged_model_refinement.h"
#include "sfm/model_edits.h"
#include "sfm/test_place.h"

namespace tmr {
namespace {

namespace fs = std::filesystem;

class ClusterMergeTest : public PlaceModelsTest {};

// A leaf model holds its kernel's images where the kernel model has them,
// so it aligns on them; a leaf whose own images a mapper placed badly (here:
// moved as a rigid group, their views of kernel points split off into
// points of their own) must still be left out of the cluster model.
TEST_F(ClusterMergeTest, ALeafPlacedBadlyIsLeftOutOfItsCluster) {
  const std::vector<colmap::image_t> place = Images("place0/");
  const size_t half = place.size() / 2;
  colmap::Reconstruction bad = Keep(place);
  MoveGroupApart({place.begin() + half, place.end()},
                 colmap::Rigid3d(Eigen::Quaterniond(Eigen::AngleAxisd(
                                     0.05, Eigen::Vector3d::UnitZ())),
                                 Eigen::Vector3d(2, -1, 0.5)),
                 &bad);
  const fs::path work = dir_ / "leaf_merge";
  fs::create_directories(work / "kernel");
  fs::create_directories(work / "bad");
  fs::create_directories(work / "good");
  Keep({place.begin(), place.begin() + half}).WriteBinary(work / "kernel");
  bad.WriteBinary(work / "bad");
  Keep(place).WriteBinary(work / "good");

  MergedModelAdjustment no_adjustment;
  no_adjustment.enabled = false;
  const ClusterMerge merge =
      MergeLeafModels(work / "kernel", {work / "bad", work / "good"}, *cache_,
                      colmap::IncrementalPipelineOptions(), 12, no_adjustment);
  EXPECT_EQ(merge.num_merged, 1);
  ASSERT_EQ(merge.left_out.size(), 1u);
  EXPECT_EQ(merge.left_out[0].leaf, 0);
  EXPECT_NE(merge.left_out[0].reason.find("shared tracks reproject"),
            std::string::npos)
      << merge.left_out[0].reason;
  EXPECT_EQ(merge.model->NumRegImages(), place.size());
}

}  // namespace
}  // namespace tmr
