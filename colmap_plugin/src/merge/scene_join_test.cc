// Copyright (c) 2026, the tmr authors. BSD-3-Clause.
// SceneAssembler::PlaceJoin on alignments given by hand: what the join of a
// merge stage by parts makes of its pairs of groups' alignments.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <string>
#include <vector>

#include "merge/scene_assembly.h"

namespace tmr {
namespace {

class PlaceJoinTest : public ::testing::Test {
 protected:
  // An assembler without correspondences (PlaceJoin needs none) for a
  // scene of 200 images: Mapper.min_model_size (10) is the smallest model
  // kept.
  std::vector<JoinedScene> Place(const std::vector<JoinModel>& models,
                                 std::vector<ModelPairAlignment> pairs) {
    const SceneAssembler assembler(
        SceneAssemblyOptions(), std::make_shared<colmap::DatabaseCache>(), "",
        std::vector<std::string>(200, "image"),
        [this](const TmrTaskReport& row) { rows_.push_back(row); });
    return assembler.PlaceJoin(models, std::move(pairs), &weak_links_);
  }

  // Models 0 and 1 aligned: 1 sits in 0's frame at twice its scale, 5 m
  // along x; four points of model 1 on their seam.
  static ModelPairAlignment Aligned() {
    ModelPairAlignment pair;
    pair.model1 = 0;
    pair.model2 = 1;
    pair.num_pairs = 12;
    pair.num_correspondences = 600;
    pair.alignment.success = true;
    pair.alignment.target_from_source = colmap::Sim3d(
        2, Eigen::Quaterniond::Identity(), Eigen::Vector3d(5, 0, 0));
    SimilarityLink link;
    link.model1 = 0;
    link.model2 = 1;
    link.model1_from_model2 = pair.alignment.target_from_source;
    link.points2 = {{0, 0, 10}, {1, 0, 10}, {0, 1, 10}, {1, 1, 11}};
    link.scale2 = 10;
    pair.link = link;
    return pair;
  }

  std::vector<TmrTaskReport> rows_;
  std::vector<TmrWeakLink> weak_links_;
};

TEST_F(PlaceJoinTest, LinkedModelsMakeOneSceneWithOneCopyOfEachImage) {
  // Images 100 and 101 are on the seam of both models: 100 keeps model 0's
  // copy (more points), 101 model 1's.
  const std::vector<JoinModel> models = {{50, {{100, 30}, {101, 10}}},
                                         {40, {{100, 20}, {101, 12}}}};
  const std::vector<JoinedScene> scenes = Place(models, {Aligned()});
  ASSERT_EQ(scenes.size(), 1u);
  EXPECT_EQ(scenes[0].num_images, 88u);
  ASSERT_EQ(scenes[0].pieces.size(), 2u);
  const JoinPiece& first = scenes[0].pieces[0];
  const JoinPiece& second = scenes[0].pieces[1];
  EXPECT_EQ(first.model, 0);
  EXPECT_EQ(first.dropped_images, std::vector<colmap::image_t>{101});
  EXPECT_NEAR(first.scene_from_model.scale(), 1.0, 1e-12);
  EXPECT_EQ(second.model, 1);
  EXPECT_EQ(second.dropped_images, std::vector<colmap::image_t>{100});
  EXPECT_NEAR(second.scene_from_model.scale(), 2.0, 1e-6);
  EXPECT_LT(
      (second.scene_from_model.translation() - Eigen::Vector3d(5, 0, 0)).norm(),
      1e-6);
  EXPECT_TRUE(weak_links_.empty());
  // The step's row, then the link's, held.
  ASSERT_EQ(rows_.size(), 2u);
  EXPECT_EQ(rows_[0].name, "align 1 linked pairs of 2 models at once");
  EXPECT_TRUE(rows_[1].success);
  EXPECT_EQ(rows_[1].link, (std::vector<int>{0, 1, 50, 40}));
}

TEST_F(PlaceJoinTest, UnalignedModelsStayApartAndSmallOnesGo) {
  ModelPairAlignment refused = Aligned();
  refused.alignment = ModelAlignment();
  refused.alignment.reason = "only 3 shared tracks";
  refused.link.reset();
  // Model 2 (5 images) joins no one: below the smallest model kept.
  const std::vector<JoinModel> models = {{40, {}}, {50, {}}, {5, {}}};
  const std::vector<JoinedScene> scenes = Place(models, {refused});
  ASSERT_EQ(scenes.size(), 2u);
  EXPECT_EQ(scenes[0].num_images, 50u);  // largest first
  EXPECT_EQ(scenes[0].pieces[0].model, 1);
  EXPECT_EQ(scenes[1].num_images, 40u);
  ASSERT_EQ(weak_links_.size(), 1u);
  EXPECT_EQ(weak_links_[0].model1, 0);
  EXPECT_EQ(weak_links_[0].model2, 1);
  EXPECT_EQ(weak_links_[0].num_pairs, 12);
  EXPECT_EQ(weak_links_[0].num_correspondences, 600);
  EXPECT_EQ(weak_links_[0].reason, "only 3 shared tracks");
  ASSERT_FALSE(rows_.empty());
  EXPECT_EQ(rows_.back().name,
            "drop 1 models of fewer than 10 images (Mapper.min_model_size)");
}

}  // namespace
}  // namespace tmr
