// Copyright (c) 2026, the tmr authors. BSD-3-Clause.
#include "tmr/partition/cluster_halo.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <tuple>

namespace tmr {
namespace {

// Images 0..n-1 with the given verified pairs (i, j, matches).
MatchGraph Graph(int num_images, std::vector<std::tuple<int, int, int>> pairs) {
  MatchGraph graph;
  for (int i = 0; i < num_images; ++i) {
    graph.images.push_back({static_cast<uint32_t>(i + 1),
                            "img" + std::to_string(i), 1, 2000, 1000});
  }
  std::sort(pairs.begin(), pairs.end());
  for (const auto& [i, j, n] : pairs) graph.pairs.push_back({i, j, n, 2});
  return graph;
}

// Cluster 0: images 0-9; cluster 1: images 10-19; image 20 unclustered.
// Matches into the other cluster: images 15, 10, 16, 11, 12 (400, 300, 300,
// 200, 120) and 13 (60) into cluster 0; images 8, 9, 2, 0, 1, 3 (400, 300,
// 200, 150, 150, 120) and 4 (60) into cluster 1; image 20 matches both.
MatchGraph TwoClusters() {
  std::vector<std::tuple<int, int, int>> pairs;
  for (int i = 0; i + 1 < 10; ++i) pairs.emplace_back(i, i + 1, 500);
  for (int i = 10; i + 1 < 20; ++i) pairs.emplace_back(i, i + 1, 500);
  pairs.emplace_back(0, 10, 150);
  pairs.emplace_back(1, 10, 150);
  pairs.emplace_back(2, 11, 200);
  pairs.emplace_back(3, 12, 120);
  pairs.emplace_back(4, 13, 60);
  pairs.emplace_back(8, 15, 400);
  pairs.emplace_back(9, 16, 300);
  pairs.emplace_back(5, 20, 900);
  pairs.emplace_back(15, 20, 900);
  return Graph(21, pairs);
}

std::vector<int> ClusterOf() {
  std::vector<int> cluster(21, 0);
  for (int i = 10; i < 20; ++i) cluster[i] = 1;
  cluster[20] = -1;
  return cluster;
}

TEST(ClusterHalo, StrongestImagesOfEachNeighbourUpToTheLimits) {
  const MatchGraph graph = TwoClusters();
  ClusterHaloOptions options;
  options.images_per_neighbour = 10;
  options.min_matches = 100;
  options.max_share = 1.0;
  std::vector<std::vector<int>> halos =
      FindClusterHalos(graph, ClusterOf(), 2, options);
  ASSERT_EQ(halos.size(), 2u);
  // Image 13 has too few matches; unclustered image 20 joins no halo.
  EXPECT_EQ(halos[0], (std::vector<int>{10, 11, 12, 15, 16}));
  EXPECT_EQ(halos[1], (std::vector<int>{0, 1, 2, 3, 8, 9}));

  options.images_per_neighbour = 2;
  halos = FindClusterHalos(graph, ClusterOf(), 2, options);
  EXPECT_EQ(halos[0], (std::vector<int>{10, 15}));  // 400, then 10 before 16

  options.images_per_neighbour = 10;
  options.max_share = 0.1;  // one image of ten
  halos = FindClusterHalos(graph, ClusterOf(), 2, options);
  EXPECT_EQ(halos[0], std::vector<int>{15});
  EXPECT_EQ(halos[1], std::vector<int>{8});

  options.images_per_neighbour = 0;
  halos = FindClusterHalos(graph, ClusterOf(), 2, options);
  EXPECT_TRUE(halos[0].empty() && halos[1].empty());

  options.images_per_neighbour = -1;
  EXPECT_THROW(FindClusterHalos(graph, ClusterOf(), 2, options),
               std::invalid_argument);
}

TEST(ClusterHalo, EachHaloImageGoesToTheLeafItMatchesMost) {
  const MatchGraph graph = TwoClusters();
  // Cluster 0 with leaves {0, 1, 2} and {3, 4}; halo images 10 (matches
  // leaf 0), 12 (matches leaf 1), 19 (matches neither: the smaller leaf).
  const std::vector<std::vector<int>> leaves = {{0, 1, 2}, {3, 4}};
  const auto assigned = AssignHaloToLeaves(graph, leaves, {10, 12, 19});
  ASSERT_EQ(assigned.size(), 2u);
  EXPECT_EQ(assigned[0], std::vector<int>{10});
  EXPECT_EQ(assigned[1], (std::vector<int>{12, 19}));
  EXPECT_TRUE(AssignHaloToLeaves(graph, {}, {10}).empty());
}

}  // namespace
}  // namespace tmr
