// Copyright (c) 2026, the tmr authors. BSD-3-Clause.
#include "tmr/partition/exemplar.h"

#include <gtest/gtest.h>

#include <cmath>

#include "partition/test_graphs.h"

namespace tmr {
namespace {

// Points on a line in two groups; similarity = -squared distance and the
// median similarity as preference: the exemplars are the group centres.
TEST(AffinityPropagation, FindsTheCentresOfTwoGroups) {
  const std::vector<double> x = {0.0,  1.0,  2.0,  1.2,  0.8,
                                 10.0, 11.0, 12.0, 10.9, 11.1};
  const int n = static_cast<int>(x.size());
  std::vector<double> s(n * n);
  std::vector<double> off;
  for (int i = 0; i < n; ++i) {
    for (int k = 0; k < n; ++k) {
      s[i * n + k] = -(x[i] - x[k]) * (x[i] - x[k]);
      if (i != k) off.push_back(s[i * n + k]);
    }
  }
  std::sort(off.begin(), off.end());
  for (int i = 0; i < n; ++i) s[i * n + i] = off[off.size() / 2];
  const std::vector<int> exemplars = AffinityPropagation(s, n, {});
  EXPECT_EQ(exemplars, (std::vector<int>{1, 6}));
  AffinityPropagationOptions other_seed;
  other_seed.seed = 99;
  EXPECT_EQ(AffinityPropagation(s, n, other_seed), exemplars);
}

TEST(AffinityPropagation, SmallInputs) {
  EXPECT_TRUE(AffinityPropagation({}, 0, {}).empty());
  EXPECT_EQ(AffinityPropagation({0.0}, 1, {}), std::vector<int>{0});
  const size_t num_exemplars =
      AffinityPropagation({0.0, 0.0, 0.0, 0.0}, 2, {}).size();
  EXPECT_GE(num_exemplars, 1u);
  EXPECT_LE(num_exemplars, 2u);
}

// Eq. 5 by hand: v0 has neighbours v1 (s=0.5, degree 2) and v2 (s=0.3,
// degree 1): delta = 2 + 100 * 0.4 + 1 * 1.5.
TEST(ExemplarScore, MatchesEquationFive) {
  const ImageGraph s(4, {{0, 1, 0.5}, {0, 2, 0.3}, {1, 3, 0.1}});
  EXPECT_DOUBLE_EQ(ExemplarScore(s, 0, 100, 1), 2 + 40 + 1.5);
  EXPECT_DOUBLE_EQ(ExemplarScore(ImageGraph(1, {}), 0, 100, 1), 0.0);
}

// A hub linked to every other kernel image (s = 0.3) of a ring (s = 0.2) is
// the exemplar. Its second image has many matches but is no near-duplicate:
// image 3 (s = 0.4) beats image 5 (s = 0.9, whose ring edges are weak).
TEST(SelectExemplar, PicksTheHubAndAWideBaselinePartner) {
  std::vector<WeightedEdge> edges;
  for (int v = 1; v < 8; ++v)
    edges.push_back({0, v, v == 3 ? 0.4 : v == 5 ? 0.9 : 0.3});
  for (int v = 1; v + 1 < 8; ++v) {
    edges.push_back({v, v + 1, (v == 4 || v == 5) ? 0.05 : 0.2});
  }
  const MatchGraph graph = test::MatchGraphWithSimilarities(8, edges);
  const ImageGraph s = BuildSimilarityGraph(graph);
  const KernelSeed seed =
      SelectExemplar(s, graph, {0, 1, 2, 3, 4, 5, 6, 7}, {});
  EXPECT_EQ(seed.exemplar, 0);
  ASSERT_EQ(seed.second_images.size(), 5u);
  EXPECT_EQ(seed.second_images[0], 3);
  EXPECT_EQ(std::count(seed.second_images.begin(), seed.second_images.end(), 5),
            0);
  EXPECT_FALSE(seed.ap_centres.empty());
}

TEST(ExemplarOptions, RejectsNanAndInfinity) {
  ExemplarOptions options;
  EXPECT_TRUE(options.Check(nullptr));
  options.beta1 = std::nan("");
  EXPECT_FALSE(options.Check(nullptr));
  options = ExemplarOptions();
  options.ap.damping = std::nan("");
  EXPECT_FALSE(options.Check(nullptr));
}

}  // namespace
}  // namespace tmr
