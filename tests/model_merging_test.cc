// Copyright (c) 2026, the tmr authors. BSD-3-Clause.
// The scene-merge rules (AlignModelsBySharedTracks,
// AlignModelsByRegisteredImages) on models cut from a tmr_synth ground
// truth, with the correspondence graph of its database as COLMAP loads it:
// disjoint halves of one place align with the similarity that was applied;
// an unlinked place, a source whose other images disagree with the anchor
// image (a wrong merge) and a source wrongly put together stay apart.
#include <colmap/geometry/sim3.h>
#include <colmap/scene/database.h>
#include <colmap/scene/database_cache.h>
#include <colmap/scene/reconstruction.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <unordered_set>

#include "evaluation/evaluate_reconstruction.h"
#include "io/model_files.h"
#include "merge/cluster_merge.h"
#include "merge/merged_model_refinement.h"
#include "merge/shared_track_alignment.h"
#include "sfm/model_edits.h"
#include "merge/registration_alignment.h"
#include "merge/scene_assembly.h"
#include "test_scene.h"

namespace tmr {
namespace {

namespace fs = std::filesystem;

class ModelMergingTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    // One place of 30 photos and one that nothing links to.
    SyntheticSceneOptions options;
    options.num_places = 1;
    options.num_unlinked_places = 1;
    options.cameras_per_place = 30;
    options.place_distance = 100;
    std::string error;
    dir_ = WriteTestScene("model_merging_test", options, &error);
    ASSERT_FALSE(dir_.empty()) << error;
    gt_ = new colmap::Reconstruction(ReadModel((dir_ / "gt").string()));
    cache_ = new std::shared_ptr<colmap::DatabaseCache>(
        LoadTestCache(dir_ / "database.db"));
  }
  static void TearDownTestSuite() {
    delete gt_;
    delete cache_;
    fs::remove_all(dir_);
  }

  // The ground truth with only the given images registered.
  static colmap::Reconstruction Keep(
      const std::vector<colmap::image_t>& images) {
    colmap::Reconstruction model = *gt_;
    for (const colmap::image_t id : gt_->RegImageIds()) {
      if (std::find(images.begin(), images.end(), id) == images.end())
        model.DeRegisterFrame(model.Image(id).FrameId());
    }
    return model;
  }

  // Registered images of the ground truth whose name starts with `prefix`,
  // by id.
  static std::vector<colmap::image_t> Images(const std::string& prefix) {
    std::vector<colmap::image_t> ids;
    for (const colmap::image_t id : gt_->RegImageIds()) {
      if (gt_->Image(id).Name().rfind(prefix, 0) == 0) ids.push_back(id);
    }
    std::sort(ids.begin(), ids.end());
    return ids;
  }

  static inline fs::path dir_;
  static inline colmap::Reconstruction* gt_ = nullptr;
  static inline std::shared_ptr<colmap::DatabaseCache>* cache_ = nullptr;
};

const colmap::Sim3d kMoved(2.5,
                           Eigen::Quaterniond(Eigen::AngleAxisd(
                               0.7,
                               Eigen::Vector3d(0.2, 1.0, -0.4).normalized())),
                           Eigen::Vector3d(14, -3, 8));

TEST_F(ModelMergingTest, DisjointHalvesOfAPlaceAlign) {
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

TEST_F(ModelMergingTest, DisjointHalvesAlignByRegisteredImages) {
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

TEST_F(ModelMergingTest, AnUnlinkedPlaceRegistersNoImage) {
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
TEST_F(ModelMergingTest, ASourceWronglyPutTogetherDoesNotAlignByImages) {
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

// A model COLMAP's mapper has continued holds every image of the database,
// most unregistered (Keep does the same); appended images must still be
// registered there, with the source's poses and tracks.
TEST_F(ModelMergingTest, AppendRegistersImagesTheTargetHoldsUnregistered) {
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

// Completion's check: of the images registered after `before`, those that
// see fewer than N points also seen by an image of `before` are taken out.
TEST_F(ModelMergingTest, CompletionTakesOutImagesWithFewPointsOfTheModel) {
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

TEST_F(ModelMergingTest, AnUnlinkedPlaceStaysApart) {
  const colmap::Reconstruction target = Keep(Images("place0/"));
  const colmap::Reconstruction source = Keep(Images("place1/"));
  ASSERT_GT(source.NumRegImages(), 0u);
  const ModelAlignment a = AlignModelsBySharedTracks(
      target, source, *(*cache_)->CorrespondenceGraph(),
      ModelAlignmentOptions());
  EXPECT_FALSE(a.success);
  EXPECT_LE(a.num_shared_tracks, 12) << a.reason;
}

TEST_F(ModelMergingTest, ASourceThatFitsOnlyAtItsAnchorImageStaysApart) {
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

// A leaf model holds its kernel's images where the kernel model has them,
// so it aligns on them; a leaf whose own images a mapper placed badly (here:
// moved as a rigid group, their views of kernel points split off into
// points of their own) must still be left out of the cluster model.
TEST_F(ModelMergingTest, ALeafPlacedBadlyIsLeftOutOfItsCluster) {
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
