// Copyright (c) 2026, the tmr authors. BSD-3-Clause.
#include "tmr/partition/image_clustering.h"

#include <gtest/gtest.h>

#include "partition/test_graphs.h"

namespace tmr {
namespace {

// The paper's Fig. 5 on D: W reaches exemplar E1 by a short path with one
// weak edge (0.14 + 0.66 + 0.18 = 0.98) and exemplar E2 by a longer path of
// even edges (4 x 0.3 = 1.2). MSP takes the even path; one layer (a plain
// shortest path) takes the short one.
TEST(MultiLayerShortestPath, EvenPathBeatsShorterPathWithWeakEdge) {
  enum { E1, R1, R2, W, G1, G2, G3, E2, N };
  const ImageGraph d(N, {{E1, R1, 0.14},
                         {R1, R2, 0.66},
                         {R2, W, 0.18},
                         {W, G3, 0.3},
                         {G3, G2, 0.3},
                         {G2, G1, 0.3},
                         {G1, E2, 0.3}});
  const std::vector<std::vector<int>> kernels = {{E1}, {E2}};
  MultiLayerShortestPathOptions options;
  options.min_bridge_side = 0;  // every edge of this path is a bridge
  const ImageClusters msp =
      AssignByMultiLayerShortestPath(d, kernels, {E1, E2}, options);
  EXPECT_EQ(msp.cluster[W], 1);
  EXPECT_EQ(msp.cluster[R1], 0);
  EXPECT_EQ(msp.cluster[G2], 1);
  EXPECT_NEAR(msp.path_length[W], 1.2, 1e-12);
  EXPECT_EQ(msp.layer[R1], 1);
  EXPECT_GT(msp.layer[W], 1);
  EXPECT_LT(msp.layer[W], options.num_layers);

  options.num_layers = 1;
  const ImageClusters plain =
      AssignByMultiLayerShortestPath(d, kernels, {E1, E2}, options);
  EXPECT_EQ(plain.cluster[W], 0);
  EXPECT_NEAR(plain.path_length[W], 0.98, 1e-12);
}

TEST(MultiLayerShortestPath,
     KernelImagesStayAndUnreachableImagesAreUnclustered) {
  // 0-1-2 kernel {0, 1} exemplar 0; 3 is isolated; 4-5 form a part without
  // a kernel.
  const ImageGraph d(6, {{0, 1, 0.2}, {1, 2, 0.9}, {4, 5, 0.5}});
  const ImageClusters result =
      AssignByMultiLayerShortestPath(d, {{0, 1}}, {0}, {});
  EXPECT_EQ(result.cluster, (std::vector<int>{0, 0, 0, -1, -1, -1}));
  EXPECT_EQ(result.layer[2], 20);
}

// X's shortest path to exemplar E1 passes through K2, an image of the other
// kernel: X joins K2's cluster, the first clustered image on its path, so
// that every cluster is connected through its own images.
TEST(MultiLayerShortestPath, PathThroughAnotherClusterJoinsThatCluster) {
  enum { E1, K2, E2, X, Y, N };
  const ImageGraph d(
      N,
      {{E1, K2, 0.1}, {K2, E2, 0.5}, {K2, X, 0.1}, {X, Y, 0.1}, {E1, Y, 0.9}});
  const ImageClusters result =
      AssignByMultiLayerShortestPath(d, {{E1}, {K2, E2}}, {E1, E2}, {});
  EXPECT_EQ(result.cluster[X], 1);
  EXPECT_EQ(result.cluster[Y], 1);
  EXPECT_NEAR(result.path_length[X], 0.2, 1e-12);
}

// The paper's rule (min_bridge_side 0): the chain of single pairs between
// the groups splits by distance, its first images to A, its last to B.
TEST(MultiLayerShortestPath, TwoGroupsSplitAtTheChain) {
  const test::TwoGroups scene(18, 30, /*with_chain=*/true);
  const ImageGraph d = BuildDifferenceGraph(BuildSimilarityGraph(
      test::MatchGraphWithSimilarities(scene.num_images, scene.edges)));
  MultiLayerShortestPathOptions options;
  options.min_bridge_side = 0;
  const ImageClusters result = AssignByMultiLayerShortestPath(
      d, {scene.group_a, scene.group_b}, {scene.group_a[0], scene.group_b[0]},
      options);
  for (const int v : scene.leaves_a) EXPECT_EQ(result.cluster[v], 0) << v;
  for (const int v : scene.leaves_b) EXPECT_EQ(result.cluster[v], 1) << v;
  EXPECT_EQ(result.cluster[scene.chain_images.front()], 0);
  EXPECT_EQ(result.cluster[scene.chain_images.back()], 1);
}

// A group of 9 images that one pair (a false pair, say) links to a kernel's
// place stays out of that kernel's cluster; a photo on its own single pair
// still joins, and so does a group linked by two pairs.
TEST(MultiLayerShortestPath, SinglePairLinksPullNoGroupIntoACluster) {
  std::vector<WeightedEdge> edges;
  auto clique = [&](int first, int size, double d) {
    for (int i = first; i < first + size; ++i) {
      for (int j = i + 1; j < first + size; ++j) edges.push_back({i, j, d});
    }
  };
  clique(0, 10, 0.5);              // the kernel's place, 0-9
  clique(10, 9, 0.6);              // a group behind one pair, 10-18
  edges.push_back({3, 12, 0.95});  // that pair
  edges.push_back({5, 19, 0.9});   // a lone photo, 19
  clique(20, 4, 0.6);              // a group behind two pairs, 20-23
  edges.push_back({1, 20, 0.9});
  edges.push_back({2, 21, 0.9});
  const ImageGraph d(24, edges);
  std::vector<int> kernel(10);
  for (int v = 0; v < 10; ++v) kernel[v] = v;
  const ImageClusters result =
      AssignByMultiLayerShortestPath(d, {kernel}, {0}, {});
  for (int v = 10; v < 19; ++v) EXPECT_EQ(result.cluster[v], -1) << v;
  EXPECT_EQ(result.cluster[19], 0);
  for (int v = 20; v < 24; ++v) EXPECT_EQ(result.cluster[v], 0) << v;

  MultiLayerShortestPathOptions paper;
  paper.min_bridge_side = 0;
  EXPECT_EQ(AssignByMultiLayerShortestPath(d, {kernel}, {0}, paper).cluster,
            std::vector<int>(24, 0));

  // A kernel that holds both sides of the pair keeps it, so that its
  // exemplar reaches all its images.
  std::vector<int> both_sides = kernel;
  for (int v = 10; v < 19; ++v) both_sides.push_back(v);
  EXPECT_EQ(AssignByMultiLayerShortestPath(d, {both_sides}, {0}, {}).cluster,
            std::vector<int>(24, 0));
}

}  // namespace
}  // namespace tmr
