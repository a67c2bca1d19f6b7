// Copyright (c) 2026, the tmr authors. BSD-3-Clause.
#include "merge/similarity_averaging.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <random>

namespace tmr {
namespace {

// Models of one scene, each in its own random similarity frame, and links
// measured on points between them, as the scene assembly's pairwise
// alignments would give them.
class Scene {
 public:
  explicit Scene(int num_models, unsigned seed = 1) : random_(seed) {
    std::uniform_real_distribution<double> angle(-M_PI, M_PI), log_s(-1, 1),
        shift(-50, 50);
    for (int m = 0; m < num_models; ++m) {
      // Model m sits around (30 m, 0, 0) in the world, in a frame of its own.
      centers_.emplace_back(30.0 * m, 0, 0);
      const Eigen::Quaterniond rotation(Eigen::AngleAxisd(
          angle(random_),
          Eigen::Vector3d(angle(random_), angle(random_), 1).normalized()));
      world_from_model_.emplace_back(
          std::exp(log_s(random_)), rotation,
          Eigen::Vector3d(shift(random_), shift(random_), shift(random_)));
    }
  }

  // A link between models a and b, off by `noise` of the viewing distance
  // (10 m) in each coordinate, then by `error` if given.
  SimilarityLink Link(int a, int b, double noise,
                      const colmap::Sim3d& error = colmap::Sim3d()) {
    SimilarityLink link;
    link.model1 = a;
    link.model2 = b;
    std::normal_distribution<double> normal(0, noise * 10);
    const Eigen::Vector3d seam = (centers_[a] + centers_[b]) / 2;
    std::uniform_real_distribution<double> around(-5, 5);
    const colmap::Sim3d b_from_world = colmap::Inverse(world_from_model_[b]);
    for (int i = 0; i < 100; ++i) {
      const Eigen::Vector3d x =
          seam + Eigen::Vector3d(around(random_), around(random_), 1);
      link.points2.push_back(b_from_world * x);
    }
    link.scale2 = 10 / world_from_model_[b].scale();
    // A small scaling, rotation and shift about the seam from the noise:
    // the link's fit error.
    const double s = 1 + normal(random_) / 10;
    const Eigen::Quaterniond r(
        Eigen::AngleAxisd(normal(random_) / 10, Eigen::Vector3d::UnitZ()));
    const colmap::Sim3d wobble(
        s, r,
        seam - s * (r * seam) +
            Eigen::Vector3d(normal(random_), normal(random_), normal(random_)));
    link.model1_from_model2 = colmap::Inverse(world_from_model_[a]) * error *
                              wobble * world_from_model_[b];
    link.weight = 100;
    return link;
  }

  int NumModels() const { return static_cast<int>(centers_.size()); }

  // How far `placed` (a's part frame from model m) puts model m's centre
  // from where it is relative to model `frame`, over the viewing distance.
  double PlacementError(const SimilarityAveraging& placed, int frame,
                        int m) const {
    const colmap::Sim3d truth =
        colmap::Inverse(world_from_model_[frame]) * world_from_model_[m];
    const Eigen::Vector3d x =
        colmap::Inverse(world_from_model_[m]) * centers_[m];
    return (truth * x - placed.part_from_model[m] * x).norm() /
           (10 / world_from_model_[frame].scale());
  }

 private:
  std::mt19937 random_;
  std::vector<Eigen::Vector3d> centers_;
  std::vector<colmap::Sim3d> world_from_model_;
};

// Models placed within this share of the viewing distance of where they
// are: the links' noise, carried over up to 120 m; a wrong link puts a
// model more than a viewing distance off.
constexpr double kPlaced = 0.05;

// Every model in model 0's part, where it is.
void ExpectOnePartAsItIs(const Scene& scene,
                         const SimilarityAveraging& placed) {
  for (int m = 0; m < scene.NumModels(); ++m) {
    EXPECT_EQ(placed.part[m], 0);
    EXPECT_LT(scene.PlacementError(placed, 0, m), kPlaced) << "model " << m;
  }
}

TEST(SimilarityAveraging, ThreeModelsOfARingArePlacedConsistently) {
  Scene scene(3);
  const std::vector<SimilarityLink> links = {scene.Link(0, 1, 0.002),
                                             scene.Link(1, 2, 0.002),
                                             scene.Link(2, 0, 0.002)};
  const SimilarityAveraging placed =
      AverageSimilarities(3, links, SimilarityAveragingOptions());
  for (int l = 0; l < 3; ++l) {
    EXPECT_TRUE(placed.accepted[l]) << placed.reason[l];
    EXPECT_LT(placed.relative_error[l], 0.05);
  }
  ExpectOnePartAsItIs(scene, placed);
}

TEST(SimilarityAveraging, AWrongLinkAcrossARingIsRefused) {
  Scene scene(4);
  // A ring of four right links, and one across it, from 0 to 2, made wrong
  // on purpose: turned by 20 degrees and 15 m off.
  const colmap::Sim3d wrong(
      1.0,
      Eigen::Quaterniond(Eigen::AngleAxisd(0.35, Eigen::Vector3d::UnitZ())),
      Eigen::Vector3d(15, 0, 0));
  std::vector<SimilarityLink> links = {
      scene.Link(0, 1, 0.002), scene.Link(1, 2, 0.002), scene.Link(2, 3, 0.002),
      scene.Link(3, 0, 0.002), scene.Link(0, 2, 0.002, wrong)};
  links.back().weight = 1000;  // stronger than any right link
  const SimilarityAveraging placed =
      AverageSimilarities(4, links, SimilarityAveragingOptions());
  EXPECT_FALSE(placed.accepted[4]);
  EXPECT_NE(placed.reason[4].find("loops of three models"), std::string::npos)
      << placed.reason[4];
  for (int l = 0; l < 4; ++l)
    EXPECT_TRUE(placed.accepted[l]) << placed.reason[l];
  ExpectOnePartAsItIs(scene, placed);
}

TEST(SimilarityAveraging, AWrongLinkOfALongLoopIsRefusedByTheAveraging) {
  // A loop of five models and no triangle: only the averaging sees the
  // wrong link, which keeps its error where the others agree.
  Scene scene(5);
  const colmap::Sim3d wrong(
      1.0, Eigen::Quaterniond(Eigen::AngleAxisd(0.5, Eigen::Vector3d::UnitY())),
      Eigen::Vector3d(0, 20, 0));
  const std::vector<SimilarityLink> links = {
      scene.Link(0, 1, 0.002), scene.Link(1, 2, 0.002), scene.Link(2, 3, 0.002),
      scene.Link(3, 4, 0.002), scene.Link(4, 0, 0.002, wrong)};
  const SimilarityAveraging placed =
      AverageSimilarities(5, links, SimilarityAveragingOptions());
  EXPECT_FALSE(placed.accepted[4]);
  EXPECT_NE(placed.reason[4].find("disagrees"), std::string::npos)
      << placed.reason[4];
  ExpectOnePartAsItIs(scene, placed);
}

TEST(SimilarityAveraging, UnlinkedModelsStayApart) {
  Scene scene(4);
  const std::vector<SimilarityLink> links = {scene.Link(0, 1, 0.002),
                                             scene.Link(3, 2, 0.002)};
  const SimilarityAveraging placed =
      AverageSimilarities(4, links, SimilarityAveragingOptions());
  EXPECT_EQ(placed.part, (std::vector<int>{0, 0, 2, 2}));
  EXPECT_LT(scene.PlacementError(placed, 0, 1), kPlaced);
  EXPECT_LT(scene.PlacementError(placed, 2, 3), kPlaced);
  EXPECT_TRUE(placed.part_from_model[2] == colmap::Sim3d());
}

TEST(SimilarityAveraging, MalformedLinksAreProgrammerErrors) {
  Scene scene(2);
  std::vector<SimilarityLink> links = {scene.Link(0, 1, 0.0)};
  links[0].points2.clear();
  EXPECT_THROW(AverageSimilarities(2, links, SimilarityAveragingOptions()),
               std::invalid_argument);
  EXPECT_THROW(AverageSimilarities(1, {scene.Link(0, 1, 0.0)},
                                   SimilarityAveragingOptions()),
               std::invalid_argument);
}

}  // namespace
}  // namespace tmr
