// Copyright (c) 2026, the tmr authors. BSD-3-Clause.
#include "tmr/partition/kernels.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "partition/test_graphs.h"

namespace tmr {
namespace {

TEST(KernelOptions, KernelSizeAndCheck) {
  KernelOptions options;
  EXPECT_EQ(options.KernelSize(100), 30);  // never below kernel_size_floor
  EXPECT_EQ(options.KernelSize(10000), 70);
  options.kernel_size_floor = 3;  // the paper's m
  EXPECT_EQ(options.KernelSize(100), 15);
  EXPECT_EQ(options.KernelSize(4), 3);  // never below min_kernel_size
  EXPECT_TRUE(options.Check());
  options.place_core_neighbors = 0;
  EXPECT_FALSE(options.Check());
  options = KernelOptions();
  options.alpha = 0.5;
  EXPECT_FALSE(options.Check());
  options = KernelOptions();
  options.num_layers = 0;
  EXPECT_FALSE(options.Check());
  // NaN and infinity fail every range test (a command line can give them).
  for (const double bad : {std::nan(""), HUGE_VAL}) {
    options = KernelOptions();
    options.epsilon = bad;
    EXPECT_FALSE(options.Check());
    options = KernelOptions();
    options.alpha = bad;
    EXPECT_FALSE(options.Check());
    options = KernelOptions();
    options.kernel_fraction = bad;
    EXPECT_FALSE(options.Check());
  }
}

// Two dense groups of 18 (m = 15, kernels of 15..22 images) with 30 leaves
// each and a thin chain: the groups are the kernels.
TEST(FindKernels, TwoDenseGroupsJoinedByThinChain) {
  const test::TwoGroups scene(18, 30, /*with_chain=*/true);
  ASSERT_EQ(scene.num_images, 100);
  const ImageGraph s = BuildSimilarityGraph(
      test::MatchGraphWithSimilarities(scene.num_images, scene.edges));
  const std::vector<Kernel> kernels =
      FindKernels(s, test::PaperKernelOptions());
  ASSERT_EQ(kernels.size(), 2u);
  EXPECT_EQ(kernels[0].images, scene.group_a);
  EXPECT_EQ(kernels[1].images, scene.group_b);
  EXPECT_EQ(kernels[0].origin, KernelOrigin::kLayer);

  // Per dense place: the same groups (the leaves and the chain see too few
  // images to be dense), each a place.
  KernelOptions per_place = test::PaperKernelOptions();
  per_place.per_place = true;
  const std::vector<Kernel> places = FindKernels(s, per_place);
  ASSERT_EQ(places.size(), 2u);
  EXPECT_EQ(places[0].images, scene.group_a);
  EXPECT_EQ(places[1].images, scene.group_b);
  EXPECT_EQ(places[0].origin, KernelOrigin::kPlace);
}

TEST(FindKernels, DisconnectedGroups) {
  const test::TwoGroups scene(18, 30, /*with_chain=*/false);
  const ImageGraph s = BuildSimilarityGraph(
      test::MatchGraphWithSimilarities(scene.num_images, scene.edges));
  const std::vector<Kernel> kernels =
      FindKernels(s, test::PaperKernelOptions());
  ASSERT_EQ(kernels.size(), 2u);
  EXPECT_EQ(kernels[0].images, scene.group_a);
  EXPECT_EQ(kernels[1].images, scene.group_b);
}

// An oversized dense group is searched recursively and carved into kernels
// of m..alpha*m images; no image is in two kernels.
TEST(FindKernels, OversizedGroupGivesSeveralProperKernels) {
  const test::TwoGroups scene(60, 40, /*with_chain=*/false);  // Z = 200, m = 30
  const ImageGraph s = BuildSimilarityGraph(
      test::MatchGraphWithSimilarities(scene.num_images, scene.edges));
  const KernelOptions options = test::PaperKernelOptions();
  const std::vector<Kernel> kernels = FindKernels(s, options);
  ASSERT_GE(kernels.size(), 2u);
  std::vector<int> seen(scene.num_images, 0);
  for (const Kernel& k : kernels) {
    EXPECT_GE(static_cast<int>(k.images.size()), options.min_kernel_size);
    EXPECT_LE(k.images.size(), 45u);
    for (const int v : k.images) EXPECT_EQ(++seen[v], 1);
  }
}

// Weights far below a = min(s) + epsilon and chains without a dense place:
// no layer ever forms a component, yet every connected part gets a kernel;
// one below the floor is a kernel whole (nothing else it could join).
TEST(FindKernels, NeverZeroKernelsForConnectedParts) {
  std::vector<WeightedEdge> edges;
  for (int v = 0; v + 1 < 30; ++v)
    edges.push_back({v, v + 1, 0.02 + 0.001 * (v % 3)});
  for (int v = 30; v + 1 < 40; ++v) edges.push_back({v, v + 1, 0.02});
  const ImageGraph s =
      BuildSimilarityGraph(test::MatchGraphWithSimilarities(42, edges));
  const std::vector<Kernel> kernels = FindKernels(s, KernelOptions());
  ASSERT_EQ(kernels.size(), 2u);  // images 40 and 41 are isolated
  EXPECT_EQ(kernels[0].origin, KernelOrigin::kRescue);
  EXPECT_EQ(kernels[0].images.size(), 30u);
  EXPECT_EQ(kernels[1].origin, KernelOrigin::kRescue);
  EXPECT_EQ(kernels[1].images,
            (std::vector<int>{30, 31, 32, 33, 34, 35, 36, 37, 38, 39}));
}

// Places of 35 to 200 images chained by streets (Z = 430, m = 65, kernels
// of up to 97): every place has a kernel inside it, the three that fit are
// kernels whole, the streets hold none, and no kernel is below the floor.
TEST(FindKernels, AKernelForEveryDensePlaceWhateverItsSize) {
  const test::PlacesAndStreets scene({35, 90, 200, 60}, 15);
  ASSERT_EQ(scene.num_images, 430);
  const ImageGraph s = BuildSimilarityGraph(
      test::MatchGraphWithSimilarities(scene.num_images, scene.edges));
  const KernelOptions options;
  const std::vector<Kernel> kernels = FindKernels(s, options);
  std::vector<int> kernels_in_place(scene.places.size(), 0);
  for (const Kernel& kernel : kernels) {
    EXPECT_GE(static_cast<int>(kernel.images.size()),
              options.kernel_size_floor);
    int place = -1;
    for (size_t p = 0; p < scene.places.size(); ++p) {
      if (std::includes(scene.places[p].begin(), scene.places[p].end(),
                        kernel.images.begin(), kernel.images.end()))
        place = static_cast<int>(p);
    }
    ASSERT_GE(place, 0) << "a kernel outside the places";
    ++kernels_in_place[place];
    if (scene.places[place].size() <= 97u) {
      EXPECT_EQ(kernel.images, scene.places[place]);
      EXPECT_EQ(kernel.origin, KernelOrigin::kPlace);
    }
  }
  for (size_t p = 0; p < scene.places.size(); ++p)
    EXPECT_GE(kernels_in_place[p], 1) << "place " << p;

  // The paper's layers on the whole graph give the places below m no
  // kernel: the layers only keep components of m to alpha * m images.
  KernelOptions paper = options;
  paper.per_place = false;
  for (const Kernel& kernel : FindKernels(s, paper)) {
    for (const int p : {0, 3}) {
      EXPECT_FALSE(std::includes(scene.places[p].begin(), scene.places[p].end(),
                                 kernel.images.begin(), kernel.images.end()));
    }
  }
}

TEST(FindKernels, EmptyAndEdgelessGraphs) {
  EXPECT_TRUE(FindKernels(ImageGraph(0, {}), KernelOptions()).empty());
  EXPECT_TRUE(FindKernels(ImageGraph(5, {}), KernelOptions()).empty());
}

}  // namespace
}  // namespace tmr
