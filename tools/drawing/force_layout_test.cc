// Copyright (c) 2026, the tmr authors. BSD-3-Clause.
#include "drawing/force_layout.h"

#include <gtest/gtest.h>

#include <cmath>

namespace tmr {
namespace {

using Position = std::array<double, 2>;

// Two cliques of `size` images (0..size-1 and size..2*size-1), joined by
// one edge (the last).
std::vector<WeightedEdge> TwoCliques(int size) {
  std::vector<WeightedEdge> edges;
  for (int c = 0; c < 2; ++c) {
    for (int i = 0; i < size; ++i) {
      for (int j = i + 1; j < size; ++j)
        edges.push_back({c * size + i, c * size + j, 0.5});
    }
  }
  edges.push_back({0, size, 0.1});
  return edges;
}

Position Centroid(const std::vector<Position>& p, int begin, int end) {
  Position c{0, 0};
  for (int v = begin; v < end; ++v) c[0] += p[v][0], c[1] += p[v][1];
  return {c[0] / (end - begin), c[1] / (end - begin)};
}

double Distance(const Position& a, const Position& b) {
  return std::hypot(a[0] - b[0], a[1] - b[1]);
}

TEST(ForceDirectedLayout, KeepsCliquesTogetherAndApart) {
  const int size = 12;
  const auto p = ForceDirectedLayout(ImageGraph(2 * size, TwoCliques(size)));
  ASSERT_EQ(p.size(), 2u * size);
  const Position a = Centroid(p, 0, size), b = Centroid(p, size, 2 * size);
  double spread = 0;
  for (int v = 0; v < size; ++v) spread += Distance(p[v], a) / size;
  for (int v = size; v < 2 * size; ++v) spread += Distance(p[v], b) / size;
  EXPECT_LT(spread / 2, 0.5 * Distance(a, b));
}

TEST(ForceDirectedLayout, SameInputSameLayout) {
  const ImageGraph graph(20, TwoCliques(8));
  EXPECT_EQ(ForceDirectedLayout(graph), ForceDirectedLayout(graph));
  ForceLayoutOptions other;
  other.seed = 8;
  EXPECT_NE(ForceDirectedLayout(graph), ForceDirectedLayout(graph, other));
}

TEST(ForceDirectedLayout, PacksComponentsWithoutOverlap) {
  // The two cliques without their link, and four isolated images.
  std::vector<WeightedEdge> edges = TwoCliques(10);
  edges.pop_back();
  const auto p = ForceDirectedLayout(ImageGraph(24, edges));
  auto box = [&](int begin, int end) {
    std::array<double, 4> b{1e300, 1e300, -1e300, -1e300};
    for (int v = begin; v < end; ++v) {
      b[0] = std::min(b[0], p[v][0]), b[1] = std::min(b[1], p[v][1]);
      b[2] = std::max(b[2], p[v][0]), b[3] = std::max(b[3], p[v][1]);
    }
    return b;
  };
  const auto a = box(0, 10), b = box(10, 20);
  const bool apart = a[2] < b[0] || b[2] < a[0] || a[3] < b[1] || b[3] < a[1];
  EXPECT_TRUE(apart);
  for (int v = 20; v < 24; ++v) {
    for (int w = 0; w < 24; ++w) {
      if (w != v) {
        EXPECT_GT(Distance(p[v], p[w]), 0.5);
      }
    }
  }
}

TEST(ForceDirectedLayout, EmptyAndSingle) {
  EXPECT_TRUE(ForceDirectedLayout(ImageGraph()).empty());
  EXPECT_EQ(ForceDirectedLayout(ImageGraph(1, {})).size(), 1u);
  ForceLayoutOptions bad;
  bad.theta = -1;
  EXPECT_THROW(ForceDirectedLayout(ImageGraph(1, {}), bad),
               std::invalid_argument);
}

}  // namespace
}  // namespace tmr
