// Copyright (c) 2026, the tmr authors. BSD-3-Clause.
// The paper's merge rule (AlignModelsBySharedTracks) on models cut from a
// tmr_synth ground truth, with the correspondence graph of its database as
// COLMAP loads it: disjoint halves of one place align with the similarity
// that was applied; an unlinked place and a source whose other images
// disagree with the anchor image (a wrong merge) stay apart.
#include "merge/shared_track_alignment.h"

#include <gtest/gtest.h>

#include <string>
#include <unordered_set>
#include <vector>

#include "sfm/test_place.h"

namespace tmr {
namespace {

class SharedTrackAlignmentTest : public PlaceModelsTest {};

TEST_F(SharedTrackAlignmentTest, DisjointHalvesOfAPlaceAlign) {
  const std::vector<colmap::image_t> place = Images("place0/");
  ASSERT_GE(place.size(), 20u);
  const size_t half = place.size() / 2;
  const colmap::Reconstruction target =
      Keep({place.begin(), place.begin() + half});
  colmap::Reconstruction source = Keep({place.begin() + half, place.end()});
  source.Transform(kMoved);

  const ModelAlignment a = AlignModelsBySharedTracks(
      target, source, *(*cache_)->CorrespondenceGraph(),
      ModelAlignmentOptions());
  ASSERT_TRUE(a.success) << a.reason;
  EXPECT_GT(a.num_verified, 12);
  for (const colmap::image_t id : source.RegImageIds()) {
    const Eigen::Vector3d recovered =
        a.target_from_source * source.Image(id).ProjectionCenter();
    EXPECT_LT((recovered - gt_->Image(id).ProjectionCenter()).norm(), 1e-3);
  }
}

TEST_F(SharedTrackAlignmentTest, AnUnlinkedPlaceStaysApart) {
  const colmap::Reconstruction target = Keep(Images("place0/"));
  const colmap::Reconstruction source = Keep(Images("place1/"));
  ASSERT_GT(source.NumRegImages(), 0u);
  const ModelAlignment a = AlignModelsBySharedTracks(
      target, source, *(*cache_)->CorrespondenceGraph(),
      ModelAlignmentOptions());
  EXPECT_FALSE(a.success);
  EXPECT_LE(a.num_shared_tracks, 12) << a.reason;
}

TEST_F(SharedTrackAlignmentTest, ASourceThatFitsOnlyAtItsAnchorImageStaysApart) {
  const std::vector<colmap::image_t> place = Images("place0/");
  const size_t half = place.size() / 2;
  const colmap::Reconstruction target =
      Keep({place.begin(), place.begin() + half});
  colmap::Reconstruction source = Keep({place.begin() + half, place.end()});
  const ModelAlignment good = AlignModelsBySharedTracks(
      target, source, *(*cache_)->CorrespondenceGraph(),
      ModelAlignmentOptions());
  ASSERT_TRUE(good.success) << good.reason;
  // Every point the anchor image does not see is displaced, as when the
  // source is wrongly put together, or the anchor's tracks are repetitive
  // structure that happens to fit.
  const colmap::Image& anchor = source.Image(good.anchor_image);
  std::unordered_set<colmap::point3D_t> seen;
  for (const colmap::Point2D& p : anchor.Points2D())
    if (p.HasPoint3D()) seen.insert(p.point3D_id);
  for (const colmap::point3D_t id : source.Point3DIds()) {
    if (!seen.count(id)) source.Point3D(id).xyz += Eigen::Vector3d(6, 0, 3);
  }
  const ModelAlignment bad = AlignModelsBySharedTracks(
      target, source, *(*cache_)->CorrespondenceGraph(),
      ModelAlignmentOptions());
  EXPECT_FALSE(bad.success);
  EXPECT_EQ(bad.anchor_image, good.anchor_image);
  EXPECT_NE(bad.reason.find("other images"), std::string::npos) << bad.reason;
}

}  // namespace
}  // namespace tmr
