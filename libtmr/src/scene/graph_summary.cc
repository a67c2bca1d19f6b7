// Copyright (c) 2026, the tmr authors. BSD-3-Clause.
#include "tmr/scene/graph_summary.h"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <numeric>

namespace tmr {

std::vector<int> ConnectedComponents(const ImageGraph& graph) {
  const int n = graph.NumVertices();
  std::vector<int> label(n, -1);
  std::vector<std::vector<int>> components;
  std::vector<int> stack;
  for (int start = 0; start < n; ++start) {
    if (label[start] >= 0) continue;
    const int id = static_cast<int>(components.size());
    components.emplace_back();
    label[start] = id;
    stack.push_back(start);
    while (!stack.empty()) {
      const int v = stack.back();
      stack.pop_back();
      components[id].push_back(v);
      const auto [begin, end] = graph.Neighbors(v);
      for (auto* it = begin; it != end; ++it) {
        if (label[it->vertex] < 0) {
          label[it->vertex] = id;
          stack.push_back(it->vertex);
        }
      }
    }
  }
  // Components were found in order of their smallest vertex; a stable sort
  // by size keeps that order among equal sizes.
  std::vector<int> order(components.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) {
    return components[a].size() > components[b].size();
  });
  std::vector<int> rank(components.size());
  for (size_t r = 0; r < order.size(); ++r) rank[order[r]] = r;
  for (int& l : label) l = rank[l];
  return label;
}

GraphSummary SummarizeGraph(const MatchGraph& match_graph,
                            const ImageGraph& similarity_graph,
                            int num_histogram_bins) {
  GraphSummary summary;
  summary.num_images = match_graph.NumImages();
  summary.num_pairs = match_graph.NumPairs();
  const std::vector<int> labels = ConnectedComponents(similarity_graph);
  for (const int l : labels) {
    if (l >= static_cast<int>(summary.component_sizes.size())) {
      summary.component_sizes.resize(l + 1, 0);
    }
    ++summary.component_sizes[l];
  }
  double sum_degree = 0.0, sum_matched = 0.0;
  for (int v = 0; v < summary.num_images; ++v) {
    const int degree = similarity_graph.Degree(v);
    sum_degree += degree;
    summary.max_degree = std::max(summary.max_degree, degree);
    if (degree == 0) ++summary.num_isolated_images;
    sum_matched += match_graph.images[v].num_matched_keypoints;
  }
  if (summary.num_images > 0) {
    summary.mean_degree = sum_degree / summary.num_images;
    summary.mean_matched_keypoints = sum_matched / summary.num_images;
  }
  double sum_inliers = 0.0;
  for (const MatchGraphPair& pair : match_graph.pairs) {
    sum_inliers += pair.num_inliers;
  }
  if (summary.num_pairs > 0)
    summary.mean_inliers = sum_inliers / summary.num_pairs;

  std::vector<double> weights;
  for (const WeightedEdge& e : similarity_graph.Edges())
    weights.push_back(e.weight);
  std::sort(weights.begin(), weights.end());
  if (!weights.empty()) {
    for (const double q : {0.0, 0.1, 0.5, 0.9, 1.0}) {
      const size_t k =
          static_cast<size_t>(std::lround(q * (weights.size() - 1)));
      summary.similarity_quantiles.push_back(weights[k]);
    }
  }
  summary.similarity_histogram.assign(num_histogram_bins, 0);
  for (const double w : weights) {
    const int bin = std::clamp(static_cast<int>(w * num_histogram_bins), 0,
                               num_histogram_bins - 1);
    ++summary.similarity_histogram[bin];
  }
  return summary;
}

void PrintGraphSummary(const GraphSummary& s, std::ostream& out) {
  out << std::fixed << std::setprecision(3);
  out << "images            " << s.num_images << " (" << s.num_isolated_images
      << " without a verified pair)\n";
  out << "verified pairs    " << s.num_pairs << "\n";
  out << "components        " << s.component_sizes.size() << " (sizes:";
  const size_t shown = std::min<size_t>(s.component_sizes.size(), 10);
  for (size_t k = 0; k < shown; ++k) out << " " << s.component_sizes[k];
  if (shown < s.component_sizes.size()) out << " ...";
  out << ")\n";
  out << "degree            mean " << s.mean_degree << ", max " << s.max_degree
      << "\n";
  out << "mean n_i          " << s.mean_matched_keypoints
      << " matched keypoints per image\n";
  out << "mean n_ij         " << s.mean_inliers << " inliers per pair\n";
  if (!s.similarity_quantiles.empty()) {
    const auto& q = s.similarity_quantiles;
    out << "similarity s_ij   min " << q[0] << ", p10 " << q[1] << ", median "
        << q[2] << ", p90 " << q[3] << ", max " << q[4] << "\n";
    const int bins = static_cast<int>(s.similarity_histogram.size());
    const int peak = *std::max_element(s.similarity_histogram.begin(),
                                       s.similarity_histogram.end());
    out << "histogram of s_ij\n";
    for (int b = 0; b < bins; ++b) {
      if (s.similarity_histogram[b] == 0) continue;
      const int bar =
          peak > 0 ? (40 * s.similarity_histogram[b] + peak - 1) / peak : 0;
      out << "  [" << static_cast<double>(b) / bins << ", "
          << static_cast<double>(b + 1) / bins << (b + 1 == bins ? "] " : ") ")
          << std::setw(8) << s.similarity_histogram[b] << " "
          << std::string(bar, '#') << "\n";
    }
  }
  out << std::defaultfloat;
}

}  // namespace tmr
