// Copyright (c) 2026, the tmr authors. BSD-3-Clause.
#pragma once

#include <ostream>
#include <vector>

#include "tmr/scene/image_graph.h"
#include "tmr/scene/match_graph.h"

namespace tmr {

// Connected components of a graph: label per vertex, labels numbered by
// decreasing component size (0 = largest; ties by smallest vertex).
std::vector<int> ConnectedComponents(const ImageGraph& graph);

// Figures that describe a match graph and its similarity graph S.
struct GraphSummary {
  int num_images = 0;
  int num_pairs = 0;
  int num_isolated_images = 0;       // images without any counted pair
  std::vector<int> component_sizes;  // decreasing
  double mean_degree = 0.0;
  int max_degree = 0;
  double mean_matched_keypoints = 0.0;  // mean n_i
  double mean_inliers = 0.0;            // mean n_ij
  // Quantiles of s_ij: min, 10%, 50%, 90%, max.
  std::vector<double> similarity_quantiles;
  // Histogram of s_ij in bins of width 1/num_bins over [0, 1].
  std::vector<int> similarity_histogram;
};

GraphSummary SummarizeGraph(const MatchGraph& match_graph,
                            const ImageGraph& similarity_graph,
                            int num_histogram_bins = 20);

// Human-readable multi-line report.
void PrintGraphSummary(const GraphSummary& summary, std::ostream& out);

}  // namespace tmr
