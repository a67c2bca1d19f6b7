// Copyright (c) 2026, the tmr authors. BSD-3-Clause.
#include "tmr/scene/graph_summary.h"

#include <gtest/gtest.h>

#include <sstream>

namespace tmr {
namespace {

TEST(ConnectedComponents, LabelsByDecreasingSize) {
  // {0}, {1, 2}, {3, 4, 5}, {6}
  const ImageGraph g(7, {{1, 2, 0.1}, {3, 4, 0.2}, {4, 5, 0.3}});
  const std::vector<int> labels = ConnectedComponents(g);
  EXPECT_EQ(labels, (std::vector<int>{2, 1, 1, 0, 0, 0, 3}));
}

TEST(GraphSummary, CountsAndQuantiles) {
  MatchGraph graph;
  graph.images = {{1, "a", 1, 100, 40},
                  {2, "b", 1, 100, 40},
                  {3, "c", 1, 100, 40},
                  {4, "d", 1, 100, 0}};
  graph.pairs = {{0, 1, 20, 2}, {1, 2, 40, 2}};
  const ImageGraph s = BuildSimilarityGraph(graph);
  const GraphSummary summary = SummarizeGraph(graph, s, 10);
  EXPECT_EQ(summary.num_images, 4);
  EXPECT_EQ(summary.num_pairs, 2);
  EXPECT_EQ(summary.num_isolated_images, 1);
  EXPECT_EQ(summary.component_sizes, (std::vector<int>{3, 1}));
  EXPECT_EQ(summary.max_degree, 2);
  EXPECT_DOUBLE_EQ(summary.mean_degree, 1.0);
  EXPECT_DOUBLE_EQ(summary.mean_inliers, 30.0);
  ASSERT_EQ(summary.similarity_quantiles.size(), 5u);
  EXPECT_DOUBLE_EQ(summary.similarity_quantiles.front(), 20.0 / 60.0);
  EXPECT_DOUBLE_EQ(summary.similarity_quantiles.back(), 1.0);
  EXPECT_EQ(summary.similarity_histogram[3], 1);  // 0.333
  EXPECT_EQ(summary.similarity_histogram[9], 1);  // 1.0 in the last bin
  std::ostringstream out;
  PrintGraphSummary(summary, out);
  EXPECT_NE(out.str().find("verified pairs    2"), std::string::npos);
}

}  // namespace
}  // namespace tmr
