// Copyright (c) 2026, the tmr authors. BSD-3-Clause.
// AlignModelsByRegisteredImages on models cut from a tmr_synth ground
// truth: disjoint halves of one place align; an unlinked place registers
// no image; a source wrongly put together does not align.
#include "merge/registration_alignment.h"

#include <gtest/gtest.h>

#include <vector>

#include "sfm/model_edits.h"
#include "sfm/test_place.h"

namespace tmr {
namespace {

class RegistrationAlignmentTest : public PlaceModelsTest {};

TEST_F(RegistrationAlignmentTest, DisjointHalvesAlignByRegisteredImages) {
  const std::vector<colmap::image_t> place = Images("place0/");
  const size_t half = place.size() / 2;
  const colmap::Reconstruction target =
      Keep({place.begin(), place.begin() + half});
  colmap::Reconstruction source = Keep({place.begin() + half, place.end()});
  source.Transform(kMoved);

  RegistrationAlignmentOptions options;
  const ModelAlignment a = AlignModelsByRegisteredImages(
      target, source, *(*cache_)->CorrespondenceGraph(), options);
  ASSERT_TRUE(a.success) << a.reason;
  EXPECT_GE(a.num_registered_images, options.min_images);
  EXPECT_LE(a.num_registered_images, options.max_images);
  EXPECT_GE(2 * a.num_supporting_images, a.num_registered_images);
  // The similarity comes from the centres of images posed on noisy
  // keypoints (0.7 px), not from the exact ground-truth points: to a few
  // centimetres on a ring of 25 m (the scene's adjustment follows a merge).
  for (const colmap::image_t id : source.RegImageIds()) {
    const Eigen::Vector3d recovered =
        a.target_from_source * source.Image(id).ProjectionCenter();
    EXPECT_LT((recovered - gt_->Image(id).ProjectionCenter()).norm(), 0.1);
  }
}

TEST_F(RegistrationAlignmentTest, AnUnlinkedPlaceRegistersNoImage) {
  const colmap::Reconstruction target = Keep(Images("place0/"));
  const colmap::Reconstruction source = Keep(Images("place1/"));
  const ModelAlignment a = AlignModelsByRegisteredImages(
      target, source, *(*cache_)->CorrespondenceGraph(),
      RegistrationAlignmentOptions());
  EXPECT_FALSE(a.success);
  EXPECT_EQ(a.num_registered_images, 0) << a.reason;
}

// Each source image moved on its own: the images register on the target,
// but no one similarity carries the source's points onto their
// observations in all of them.
TEST_F(RegistrationAlignmentTest, ASourceWronglyPutTogetherDoesNotAlignByImages) {
  const std::vector<colmap::image_t> place = Images("place0/");
  const size_t half = place.size() / 2;
  const colmap::Reconstruction target =
      Keep({place.begin(), place.begin() + half});
  colmap::Reconstruction source = Keep({place.begin() + half, place.end()});
  for (size_t i = half; i < place.size(); ++i) {
    const double angle = (i % 2 ? 1 : -1) * 0.05 * (i - half + 1);
    SetPoseAndRegister(place[i],
                       colmap::Rigid3d(Eigen::Quaterniond(Eigen::AngleAxisd(
                                           angle, Eigen::Vector3d::UnitZ())),
                                       Eigen::Vector3d(0.3 * angle, 0, 0)) *
                           source.Image(place[i]).CamFromWorld(),
                       &source);
  }
  const ModelAlignment a = AlignModelsByRegisteredImages(
      target, source, *(*cache_)->CorrespondenceGraph(),
      RegistrationAlignmentOptions());
  EXPECT_FALSE(a.success) << a.num_supporting_images << " of "
                          << a.num_registered_images;
}

}  // namespace
}  // namespace tmr
