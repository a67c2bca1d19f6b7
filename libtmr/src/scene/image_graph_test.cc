// Copyright (c) 2026, the tmr authors. BSD-3-Clause.
#include "tmr/scene/image_graph.h"

#include <gtest/gtest.h>

#include <stdexcept>
#include <utility>
#include <vector>

namespace tmr {
namespace {

MatchGraph ThreeImages() {
  MatchGraph graph;
  graph.images = {{1, "a.jpg", 1, 100, 40},
                  {2, "b.jpg", 1, 100, 50},
                  {5, "c.jpg", 2, 100, 30}};
  graph.pairs = {{0, 1, 20, 2}, {1, 2, 15, 3}};
  return graph;
}

TEST(MatchGraph, FindImageIndex) {
  const MatchGraph graph = ThreeImages();
  EXPECT_EQ(graph.FindImageIndex(1), 0);
  EXPECT_EQ(graph.FindImageIndex(5), 2);
  EXPECT_EQ(graph.FindImageIndex(3), -1);
  EXPECT_EQ(graph.FindImageIndex(6), -1);
}

TEST(SimilarityGraph, JaccardOfMatchedKeypoints) {
  const ImageGraph s = BuildSimilarityGraph(ThreeImages());
  ASSERT_EQ(s.NumVertices(), 3);
  ASSERT_EQ(s.NumEdges(), 2);
  // s_01 = 20 / (40 + 50 - 20), s_12 = 15 / (50 + 30 - 15).
  EXPECT_DOUBLE_EQ(s.Weight(0, 1), 20.0 / 70.0);
  EXPECT_DOUBLE_EQ(s.Weight(1, 0), 20.0 / 70.0);
  EXPECT_DOUBLE_EQ(s.Weight(2, 1), 15.0 / 65.0);
  EXPECT_DOUBLE_EQ(s.Weight(0, 2, -1.0), -1.0);
  EXPECT_EQ(s.Degree(1), 2);
  EXPECT_EQ(s.Degree(2), 1);
  EXPECT_DOUBLE_EQ(s.MinWeight(), 15.0 / 65.0);
  EXPECT_DOUBLE_EQ(s.MaxWeight(), 20.0 / 70.0);
}

TEST(SimilarityGraph, StaysWithinZeroAndOne) {
  MatchGraph graph;
  // 30 inliers that reuse keypoints: fewer matched keypoints than inliers.
  graph.images = {{1, "a", 1, 10, 10}, {2, "b", 1, 10, 10}};
  graph.pairs = {{0, 1, 30, 2}};
  EXPECT_DOUBLE_EQ(BuildSimilarityGraph(graph).Weight(0, 1), 1.0);
}

TEST(DifferenceGraph, IsOneMinusSimilarity) {
  const ImageGraph s = BuildSimilarityGraph(ThreeImages());
  const ImageGraph d = BuildDifferenceGraph(s);
  ASSERT_EQ(d.NumEdges(), s.NumEdges());
  EXPECT_DOUBLE_EQ(d.Weight(0, 1), 1.0 - 20.0 / 70.0);
  EXPECT_DOUBLE_EQ(d.Weight(1, 2), 1.0 - 15.0 / 65.0);
}

TEST(ImageGraph, NeighborsAreSortedAndComplete) {
  const ImageGraph g(4, {{0, 3, 0.5}, {0, 1, 0.25}, {2, 0, 0.75}});
  const auto [begin, end] = g.Neighbors(0);
  ASSERT_EQ(end - begin, 3);
  EXPECT_EQ(begin[0].vertex, 1);
  EXPECT_EQ(begin[1].vertex, 2);
  EXPECT_EQ(begin[2].vertex, 3);
  EXPECT_DOUBLE_EQ(begin[1].weight, 0.75);
  EXPECT_EQ(g.Degree(3), 1);
}

TEST(ImageGraph, RejectsInvalidEdges) {
  EXPECT_THROW(ImageGraph(2, {{0, 2, 1.0}}), std::invalid_argument);
  EXPECT_THROW(ImageGraph(2, {{1, 1, 1.0}}), std::invalid_argument);
  EXPECT_THROW(ImageGraph(2, {{0, 1, 1.0}, {1, 0, 2.0}}),
               std::invalid_argument);
}

TEST(ImageGraph, EmptyGraph) {
  const ImageGraph g(3, {});
  EXPECT_EQ(g.NumEdges(), 0);
  EXPECT_EQ(g.Degree(2), 0);
  EXPECT_DOUBLE_EQ(g.MinWeight(), 0.0);
}

// Two triangles joined by the path 2-3-4 (two bridges) with a pendant
// image 7 on 0 (a bridge with one image on its side), and a separate pair
// 8-9 (a bridge of its own part).
TEST(FindBridges, OnlyPairsThatAloneLinkGroupsOfTheGivenSize) {
  const ImageGraph g(10, {{0, 1, 0.1},
                          {1, 2, 0.1},
                          {0, 2, 0.1},
                          {2, 3, 0.2},
                          {3, 4, 0.3},
                          {4, 5, 0.1},
                          {5, 6, 0.1},
                          {4, 6, 0.1},
                          {7, 0, 0.4},
                          {8, 9, 0.5}});
  auto pairs = [](const std::vector<WeightedEdge>& edges) {
    std::vector<std::pair<int, int>> result;
    for (const WeightedEdge& e : edges) result.emplace_back(e.u, e.v);
    return result;
  };
  using Pairs = std::vector<std::pair<int, int>>;
  EXPECT_EQ(pairs(FindBridges(g, 1)), (Pairs{{2, 3}, {3, 4}, {0, 7}, {8, 9}}));
  EXPECT_EQ(pairs(FindBridges(g, 2)), (Pairs{{2, 3}, {3, 4}}));
  EXPECT_EQ(pairs(FindBridges(g, 4)), (Pairs{{2, 3}}));  // sides 4 and 4
  EXPECT_TRUE(FindBridges(g, 5).empty());
  EXPECT_DOUBLE_EQ(FindBridges(g, 4)[0].weight, 0.2);
  EXPECT_TRUE(FindBridges(ImageGraph(3, {}), 1).empty());
}

}  // namespace
}  // namespace tmr
