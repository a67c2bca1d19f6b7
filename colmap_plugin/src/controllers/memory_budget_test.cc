// Copyright (c) 2026, the tmr authors. BSD-3-Clause.
#include "controllers/memory_budget.h"

#include <gtest/gtest.h>

#include "tmr/util/process.h"

namespace tmr {
namespace {

MemoryLoad Load(int64_t images, int64_t keypoints_per_image,
                int64_t matched_per_image) {
  return {images, images * keypoints_per_image, images * matched_per_image};
}

TEST(MemoryBudget, ATaskNeedsMoreWithMoreImagesAndMatches) {
  const double small = TaskPeakMiB(Load(80, 4000, 2500));
  EXPECT_GT(small, 0.0);
  EXPECT_GT(TaskPeakMiB(Load(400, 4000, 2500)), small);
  EXPECT_GT(TaskPeakMiB(Load(80, 4000, 3500)), small);
  // Keypoints without a match cost far less than matched ones.
  EXPECT_LT(TaskPeakMiB(Load(80, 8000, 2500)) - small,
            TaskPeakMiB(Load(80, 8000, 6500)) - small);
}

TEST(MemoryBudget, TheMergeStageHoldsTheCorrespondencesAndOneAdjustment) {
  const MemoryLoad scene = Load(3752, 2600, 2570);
  const double merge = MergePeakMiB(scene, 500, 1000);
  EXPECT_GT(merge, CorrespondencesMiB(scene));
  // Blocks of at most 1,000 images: smaller blocks need no more, and one
  // adjustment of the whole scene with all its points needs more.
  EXPECT_LE(MergePeakMiB(scene, 500, 250), merge);
  EXPECT_GT(MergePeakMiB(scene, 500, 0), merge);
  // Ten times the photos: about ten times the memory.
  const double large = MergePeakMiB(Load(37520, 2600, 2570), 500, 1000);
  EXPECT_GT(large, 5 * merge);
  EXPECT_LT(large, 12 * merge);
}

TEST(MemoryBudget, TheJoinAdjustsOnAsManyTracksAsTheBudgetHolds) {
  // City10 (9,768 photos, groups of up to 1,021) at 4 GiB: fewer than the
  // 500 wanted, and its adjustment then fits beside the process; at 3 GiB
  // too few to help (149), so none.
  const int tracks = JoinTracksThatFit(500, 4096.0, 9768, 1021);
  EXPECT_GE(tracks, 150);
  EXPECT_LT(tracks, 500);
  EXPECT_LE(ProcessMiB() + JoinAdjustmentMiB(9768, tracks, 1021), 4096.0);
  EXPECT_GT(ProcessMiB() + JoinAdjustmentMiB(9768, tracks + 1, 1021), 4096.0);
  EXPECT_EQ(JoinTracksThatFit(500, 3072.0, 9768, 1021), 0);
  // Fewer wanted than the minimum: as many as wanted.
  EXPECT_EQ(JoinTracksThatFit(100, 4096.0, 9768, 1021), 100);
  // A small scene gets all it wants; a budget below the process none.
  EXPECT_EQ(JoinTracksThatFit(500, 8192.0, 1000, 300), 500);
  EXPECT_EQ(JoinTracksThatFit(500, 100.0, 1000, 300), 0);
  EXPECT_EQ(JoinAdjustmentMiB(1000, 0, 300), 0.0);
}

TEST(MemoryBudget, AnOptionWinsElseHalfOfWhatTheProcessMayUse) {
  const MemoryBudget given = ResolveMemoryBudget(3.5);
  EXPECT_DOUBLE_EQ(given.mib, 3.5 * 1024);
  EXPECT_EQ(given.source, "--Tmr.memory_budget");
  const double available = AvailableMemoryMiB();
  ASSERT_GT(available, 0.0) << "Linux says its memory in /proc/meminfo";
  const MemoryBudget half = ResolveMemoryBudget(0.0);
  EXPECT_DOUBLE_EQ(half.mib, available / 2);
  EXPECT_NE(half.source.find("half of the"), std::string::npos);
}

TEST(MemoryBudget, TheMergeWarnsOnlyAboveTheBudget) {
  const MemoryBudget budget{2048.0, "--Tmr.memory_budget"};
  EXPECT_EQ(MergeOverBudgetWarning(2000.0, budget), "");
  EXPECT_EQ(MergeOverBudgetWarning(3072.0, budget),
            "warning: the merge stage is expected to need 3.00 GiB, above "
            "the memory budget of 2.00 GiB; give a budget it fits in, or run "
            "it where it fits");
  EXPECT_EQ(GiBText(1280.0), "1.25 GiB");
}

}  // namespace
}  // namespace tmr
