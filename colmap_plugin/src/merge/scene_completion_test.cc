// Copyright (c) 2026, the tmr authors. BSD-3-Clause.
// Completion's check of the images it registered (RemoveUnanchoredImages)
// on a tmr_synth place.
#include "merge/scene_assembly.h"

#include <gtest/gtest.h>

#include <unordered_set>
#include <vector>

#include "sfm/test_place.h"

namespace tmr {
namespace {

class SceneCompletionTest : public PlaceModelsTest {};

// Completion's check: of the images registered after `before`, those that
// see fewer than N points also seen by an image of `before` are taken out.
TEST_F(SceneCompletionTest, CompletionTakesOutImagesWithFewPointsOfTheModel) {
  const std::vector<colmap::image_t> place = Images("place0/");
  colmap::Reconstruction scene = Keep(place);
  const std::unordered_set<colmap::image_t> before(
      place.begin(), place.begin() + place.size() / 3);
  // Each later image's points seen by an earlier one, counted here.
  const int kMin = 30;
  std::vector<colmap::image_t> expect_kept, expect_removed;
  for (const colmap::image_t id : place) {
    if (before.count(id)) continue;
    int anchored = 0;
    for (const colmap::Point2D& p : scene.Image(id).Points2D()) {
      if (!p.HasPoint3D()) continue;
      for (const auto& el : scene.Point3D(p.point3D_id).track.Elements()) {
        if (before.count(el.image_id)) {
          ++anchored;
          break;
        }
      }
    }
    (anchored >= kMin ? expect_kept : expect_removed).push_back(id);
  }
  ASSERT_FALSE(expect_kept.empty());
  ASSERT_FALSE(expect_removed.empty());  // the far side of the ring

  EXPECT_EQ(RemoveUnanchoredImages(before, kMin, &scene),
            static_cast<int>(expect_removed.size()));
  for (const colmap::image_t id : expect_kept)
    EXPECT_TRUE(scene.Image(id).HasPose());
  for (const colmap::image_t id : expect_removed)
    EXPECT_FALSE(scene.Image(id).HasPose());
  for (const colmap::image_t id : before)
    EXPECT_TRUE(scene.Image(id).HasPose());
}

}  // namespace
}  // namespace tmr
