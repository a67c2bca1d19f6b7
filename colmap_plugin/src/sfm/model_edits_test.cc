// Copyright (c) 2026, the tmr authors. BSD-3-Clause.
#include "sfm/model_edits.h"

#include <colmap/scene/synthetic.h>
#include <gtest/gtest.h>

#include <algorithm>

#include "sfm/test_place.h"

namespace tmr {
namespace {

colmap::Reconstruction SynthesizedModel() {
  colmap::SyntheticDatasetOptions options;
  options.num_rigs = 1;
  options.num_frames_per_rig = 8;
  options.num_points3D = 120;
  options.track_length = 3;
  colmap::Reconstruction model;
  colmap::SynthesizeDataset(options, &model);
  return model;
}

TEST(MakeSeamModel, KeepsEveryPoseAndTheSeamImagesPoints) {
  const colmap::Reconstruction model = SynthesizedModel();
  const std::vector<colmap::image_t> ids = model.RegImageIds();
  const std::unordered_set<colmap::image_t> seam = {ids[0], ids[1], ids[2]};
  colmap::Reconstruction light;
  MakeSeamModel(model, seam, &light);
  ASSERT_EQ(light.NumRegImages(), model.NumRegImages());
  size_t seam_points = 0;
  for (const colmap::image_t id : ids) {
    const colmap::Image& image = light.Image(id);
    EXPECT_LT(
        (image.ProjectionCenter() - model.Image(id).ProjectionCenter()).norm(),
        1e-12);
    if (seam.count(id)) {
      EXPECT_EQ(image.NumPoints3D(), model.Image(id).NumPoints3D());
      seam_points += image.NumPoints3D();
    } else {
      EXPECT_EQ(image.NumPoints2D(), 0);
    }
  }
  EXPECT_GT(seam_points, 0);
  EXPECT_LT(light.NumPoints3D(), model.NumPoints3D());
  for (const auto& [id, point] : light.Points3D()) {
    EXPECT_EQ(point.xyz, model.Point3D(id).xyz);
    for (const colmap::TrackElement& element : point.track.Elements())
      EXPECT_TRUE(seam.count(element.image_id));
  }
}

TEST(KeepOneCopyOfEachImage, SaysWhichCopiesItDeregistered) {
  colmap::Reconstruction a = SynthesizedModel();
  colmap::Reconstruction b = a;
  const colmap::image_t id = a.RegImageIds()[0];
  // b's copy of `id` sees fewer points: a's stays.
  for (colmap::point2D_t p = 0; p < b.Image(id).NumPoints2D(); ++p) {
    if (b.Image(id).Point2D(p).HasPoint3D()) {
      b.DeleteObservation(id, p);
      break;
    }
  }
  const size_t num_images = a.NumRegImages();
  std::vector<std::vector<colmap::image_t>> dropped;
  const int removed = KeepOneCopyOfEachImage({&a, &b}, &dropped);
  // On a tie the first model's copy stays: b keeps none.
  EXPECT_EQ(removed, static_cast<int>(num_images));
  EXPECT_EQ(a.NumRegImages(), num_images);
  EXPECT_EQ(b.NumRegImages(), 0);
  ASSERT_EQ(dropped.size(), 2);
  EXPECT_TRUE(dropped[0].empty());
  EXPECT_EQ(dropped[1].size(), num_images);
  EXPECT_EQ(std::count(dropped[1].begin(), dropped[1].end(), id), 1);
}

class AppendReconstructionTest : public PlaceModelsTest {};

// A model COLMAP's mapper has continued holds every image of the database,
// most unregistered (Keep does the same); appended images must still be
// registered there, with the source's poses and tracks.
TEST_F(AppendReconstructionTest, AppendRegistersImagesTheTargetHoldsUnregistered) {
  const std::vector<colmap::image_t> place = Images("place0/");
  const size_t half = place.size() / 2;
  colmap::Reconstruction target = Keep({place.begin(), place.begin() + half});
  colmap::Reconstruction source = Keep({place.begin() + half, place.end()});
  source.Transform(kMoved);
  ASSERT_TRUE(target.ExistsImage(place.back()));
  const size_t points_before = target.NumPoints3D();

  AppendReconstruction(source, colmap::Inverse(kMoved), &target);
  EXPECT_EQ(target.NumRegImages(), place.size());
  EXPECT_GT(target.NumPoints3D(), points_before);
  for (size_t i = half; i < place.size(); ++i) {
    const colmap::Image& image = target.Image(place[i]);
    EXPECT_LT(
        (image.ProjectionCenter() - gt_->Image(place[i]).ProjectionCenter())
            .norm(),
        1e-6);
    EXPECT_GT(image.NumPoints3D(), 0u);
  }
}

}  // namespace
}  // namespace tmr
