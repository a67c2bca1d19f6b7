// Copyright (c) 2026, the tmr authors. BSD-3-Clause.
#include "tmr/partition/leaf_clustering.h"

#include <gtest/gtest.h>

#include <cmath>

#include <queue>
#include <random>
#include <set>

namespace tmr {
namespace {

// True if every image of `cluster` reaches the kernel through the cluster.
bool ReachesKernelThroughItself(const ImageGraph& d,
                                const std::vector<int>& kernel,
                                const std::vector<int>& cluster) {
  std::set<int> allowed(kernel.begin(), kernel.end());
  allowed.insert(cluster.begin(), cluster.end());
  std::set<int> seen(kernel.begin(), kernel.end());
  std::queue<int> queue;
  for (const int v : kernel) queue.push(v);
  while (!queue.empty()) {
    const int v = queue.front();
    queue.pop();
    const auto [begin, end] = d.Neighbors(v);
    for (auto* it = begin; it != end; ++it) {
      if (allowed.count(it->vertex) && seen.insert(it->vertex).second)
        queue.push(it->vertex);
    }
  }
  for (const int v : cluster) {
    if (!seen.count(v)) return false;
  }
  return true;
}

// A kernel of 5 images with 6 rays of 10 images each: with m = 5 and r = 2
// (e = 10), K_c = 6 and every ray is one leaf cluster.
TEST(RadialAgglomerateClustering, RaysBecomeBalancedLeafClusters) {
  std::vector<WeightedEdge> edges;
  for (int i = 0; i < 5; ++i) {
    for (int j = i + 1; j < 5; ++j) edges.push_back({i, j, 0.3});
  }
  std::vector<int> leaves;
  for (int ray = 0; ray < 6; ++ray) {
    int previous = ray % 5;
    for (int k = 0; k < 10; ++k) {
      const int v = 5 + ray * 10 + k;
      edges.push_back({previous, v, 0.6 + 0.01 * k});
      leaves.push_back(v);
      previous = v;
    }
    // A weaker cross link to the next ray, as neighbouring views have.
    if (ray > 0)
      edges.push_back({5 + ray * 10 + 5, 5 + (ray - 1) * 10 + 5, 0.85});
  }
  const ImageGraph d(65, edges);
  RadialAgglomerateOptions options;
  options.r = 2.0;
  const std::vector<int> kernel = {0, 1, 2, 3, 4};
  const auto clusters =
      RadialAgglomerateClustering(d, kernel, leaves, 5, options);
  ASSERT_EQ(clusters.size(), 6u);
  for (size_t c = 0; c < clusters.size(); ++c) {
    EXPECT_EQ(clusters[c].size(), 10u);
    EXPECT_EQ(clusters[c].front(), 5 + static_cast<int>(c) * 10);
    EXPECT_TRUE(ReachesKernelThroughItself(d, kernel, clusters[c]));
  }
}

// A random geometric graph around a central kernel: K_c or fewer clusters,
// sizes within a factor of the ideal one, every cluster self-reaching, and
// every leaf in exactly one cluster.
TEST(RadialAgglomerateClustering, RandomRadialSceneIsBalancedAndSelfReaching) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  const int n = 400;
  std::vector<std::pair<double, double>> xy(n);
  for (auto& p : xy) p = {unit(rng), unit(rng)};
  std::vector<int> kernel, leaves;
  for (int v = 0; v < n; ++v) {
    const double r2 = xy[v].first * xy[v].first + xy[v].second * xy[v].second;
    (r2 < 0.04 ? kernel : leaves).push_back(v);
  }
  std::vector<WeightedEdge> edges;
  for (int u = 0; u < n; ++u) {
    for (int v = u + 1; v < n; ++v) {
      const double dx = xy[u].first - xy[v].first,
                   dy = xy[u].second - xy[v].second;
      const double dist = std::sqrt(dx * dx + dy * dy);
      if (dist < 0.2) edges.push_back({u, v, 0.5 + dist});
    }
  }
  const ImageGraph d(n, edges);
  const int m = 20;  // r = 3: e = 60
  const auto clusters = RadialAgglomerateClustering(d, kernel, leaves, m, {});
  const size_t k_c = std::lround(leaves.size() / 60.0);
  EXPECT_LE(clusters.size(), k_c);
  EXPECT_GE(clusters.size(), k_c / 2);
  std::vector<int> count(n, 0);
  for (const auto& cluster : clusters) {
    EXPECT_GE(cluster.size(), 15u);
    EXPECT_LE(cluster.size(), 180u);
    EXPECT_TRUE(ReachesKernelThroughItself(d, kernel, cluster));
    for (const int v : cluster) ++count[v];
  }
  for (const int v : leaves) EXPECT_EQ(count[v], 1) << v;
}

TEST(RadialAgglomerateClustering, DetachedLeavesFormTheirOwnCluster) {
  // Kernel {0}, leaves 1, 2 (linked to the kernel) and 3-4 (only to each
  // other).
  const ImageGraph d(5, {{0, 1, 0.5}, {1, 2, 0.5}, {3, 4, 0.5}});
  const auto clusters =
      RadialAgglomerateClustering(d, {0}, {1, 2, 3, 4}, 10, {});
  EXPECT_EQ(clusters, (std::vector<std::vector<int>>{{1, 2}, {3, 4}}));
  EXPECT_TRUE(RadialAgglomerateClustering(d, {0}, {}, 10, {}).empty());
}

TEST(RadialAgglomerateOptions, RejectsNanAndInfinity) {
  RadialAgglomerateOptions options;
  EXPECT_TRUE(options.Check(nullptr));
  options.r = std::nan("");
  EXPECT_FALSE(options.Check(nullptr));
  options = RadialAgglomerateOptions();
  options.r = HUGE_VAL;  // e = r * m would not fit an int
  EXPECT_FALSE(options.Check(nullptr));
  options = RadialAgglomerateOptions();
  options.sigma3 = std::nan("");
  EXPECT_FALSE(options.Check(nullptr));
}

}  // namespace
}  // namespace tmr
