// Copyright (c) 2026, the tmr authors. BSD-3-Clause.
#include "tmr/partition/kernels.h"

#include <gtest/gtest.h>

#include <cmath>

#include "partition/test_graphs.h"

namespace tmr {
namespace {

TEST(KernelOptions, KernelSizeAndCheck) {
  KernelOptions options;
  EXPECT_EQ(options.KernelSize(100), 15);
  EXPECT_EQ(options.KernelSize(10000), 70);
  EXPECT_EQ(options.KernelSize(4), 3);  // never below min_kernel_size
  EXPECT_TRUE(options.Check());
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
  const std::vector<Kernel> kernels = FindKernels(s, KernelOptions());
  ASSERT_EQ(kernels.size(), 2u);
  EXPECT_EQ(kernels[0].images, scene.group_a);
  EXPECT_EQ(kernels[1].images, scene.group_b);
  EXPECT_EQ(kernels[0].origin, KernelOrigin::kLayer);
}

TEST(FindKernels, DisconnectedGroups) {
  const test::TwoGroups scene(18, 30, /*with_chain=*/false);
  const ImageGraph s = BuildSimilarityGraph(
      test::MatchGraphWithSimilarities(scene.num_images, scene.edges));
  const std::vector<Kernel> kernels = FindKernels(s, KernelOptions());
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
  KernelOptions options;
  const std::vector<Kernel> kernels = FindKernels(s, options);
  ASSERT_GE(kernels.size(), 2u);
  std::vector<int> seen(scene.num_images, 0);
  for (const Kernel& k : kernels) {
    EXPECT_GE(static_cast<int>(k.images.size()), options.min_kernel_size);
    EXPECT_LE(k.images.size(), 45u);
    for (const int v : k.images) EXPECT_EQ(++seen[v], 1);
  }
}

// Weights far below a = min(s) + epsilon: no layer ever forms a component,
// yet a connected scene gets a kernel, and so does every connected part.
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
  EXPECT_LT(kernels[0].images.back(), 30);
  EXPECT_GE(kernels[1].images.front(), 30);
}

TEST(FindKernels, EmptyAndEdgelessGraphs) {
  EXPECT_TRUE(FindKernels(ImageGraph(0, {}), KernelOptions()).empty());
  EXPECT_TRUE(FindKernels(ImageGraph(5, {}), KernelOptions()).empty());
}

}  // namespace
}  // namespace tmr
