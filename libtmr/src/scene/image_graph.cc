// Copyright (c) 2026, the tmr authors. BSD-3-Clause.
#include "tmr/scene/image_graph.h"

#include <algorithm>
#include <stdexcept>
#include <string>

namespace tmr {

ImageGraph::ImageGraph(int num_vertices, std::vector<WeightedEdge> edges)
    : num_vertices_(num_vertices), edges_(std::move(edges)) {
  if (num_vertices_ < 0) {
    throw std::invalid_argument("ImageGraph: negative number of vertices");
  }
  offsets_.assign(num_vertices_ + 1, 0);
  for (const WeightedEdge& e : edges_) {
    if (e.u < 0 || e.v < 0 || e.u >= num_vertices_ || e.v >= num_vertices_) {
      throw std::invalid_argument("ImageGraph: edge endpoint out of range");
    }
    if (e.u == e.v) throw std::invalid_argument("ImageGraph: self loop");
    ++offsets_[e.u + 1];
    ++offsets_[e.v + 1];
  }
  for (int v = 0; v < num_vertices_; ++v) offsets_[v + 1] += offsets_[v];
  adjacency_.resize(offsets_.back());
  std::vector<int> fill(offsets_.begin(), offsets_.end() - 1);
  for (const WeightedEdge& e : edges_) {
    adjacency_[fill[e.u]++] = {e.v, e.weight};
    adjacency_[fill[e.v]++] = {e.u, e.weight};
  }
  for (int v = 0; v < num_vertices_; ++v) {
    auto* begin = adjacency_.data() + offsets_[v];
    auto* end = adjacency_.data() + offsets_[v + 1];
    std::sort(begin, end, [](const Neighbor& a, const Neighbor& b) {
      return a.vertex < b.vertex;
    });
    for (auto* it = begin; it + 1 < end; ++it) {
      if (it->vertex == (it + 1)->vertex) {
        throw std::invalid_argument("ImageGraph: duplicate edge (" +
                                    std::to_string(v) + ", " +
                                    std::to_string(it->vertex) + ")");
      }
    }
  }
}

std::pair<const ImageGraph::Neighbor*, const ImageGraph::Neighbor*>
ImageGraph::Neighbors(int v) const {
  return {adjacency_.data() + offsets_.at(v),
          adjacency_.data() + offsets_.at(v + 1)};
}

int ImageGraph::Degree(int v) const {
  return offsets_.at(v + 1) - offsets_.at(v);
}

double ImageGraph::Weight(int u, int v, double missing) const {
  const auto [begin, end] = Neighbors(u);
  const auto it = std::lower_bound(
      begin, end, v,
      [](const Neighbor& n, int vertex) { return n.vertex < vertex; });
  return (it != end && it->vertex == v) ? it->weight : missing;
}

double ImageGraph::MinWeight() const {
  if (edges_.empty()) return 0.0;
  return std::min_element(edges_.begin(), edges_.end(),
                          [](const WeightedEdge& a, const WeightedEdge& b) {
                            return a.weight < b.weight;
                          })
      ->weight;
}

double ImageGraph::MaxWeight() const {
  if (edges_.empty()) return 0.0;
  return std::max_element(edges_.begin(), edges_.end(),
                          [](const WeightedEdge& a, const WeightedEdge& b) {
                            return a.weight < b.weight;
                          })
      ->weight;
}

ImageGraph BuildSimilarityGraph(const MatchGraph& match_graph) {
  std::vector<WeightedEdge> edges;
  edges.reserve(match_graph.pairs.size());
  for (const MatchGraphPair& pair : match_graph.pairs) {
    const double n_ij = pair.num_inliers;
    const double n_i = match_graph.images.at(pair.image1).num_matched_keypoints;
    const double n_j = match_graph.images.at(pair.image2).num_matched_keypoints;
    const double union_size = std::max(n_ij, n_i + n_j - n_ij);
    const double s_ij = union_size > 0.0 ? n_ij / union_size : 0.0;
    edges.push_back({pair.image1, pair.image2, s_ij});
  }
  return ImageGraph(match_graph.NumImages(), std::move(edges));
}

std::vector<WeightedEdge> FindBridges(const ImageGraph& graph, int min_side) {
  const int n = graph.NumVertices();
  std::vector<int> order(n, -1), low(n, 0), subtree(n, 1), parent(n, -1);
  std::vector<int> part_of(n, 0), part_size;
  std::vector<int> bridge_children;  // v of each bridge (parent[v], v)
  struct Frame {
    int v;
    const ImageGraph::Neighbor* next;
  };
  std::vector<Frame> stack;
  int time = 0;
  for (int root = 0; root < n; ++root) {
    if (order[root] >= 0) continue;
    const int part = static_cast<int>(part_size.size());
    part_size.push_back(0);
    order[root] = low[root] = time++;
    stack.push_back({root, graph.Neighbors(root).first});
    while (!stack.empty()) {
      const int v = stack.back().v;
      if (stack.back().next != graph.Neighbors(v).second) {
        const int u = (stack.back().next++)->vertex;
        if (order[u] < 0) {
          parent[u] = v;
          order[u] = low[u] = time++;
          stack.push_back({u, graph.Neighbors(u).first});
        } else if (u != parent[v]) {
          low[v] = std::min(low[v], order[u]);
        }
        continue;
      }
      stack.pop_back();
      part_of[v] = part;
      ++part_size[part];
      const int p = parent[v];
      if (p < 0) continue;
      low[p] = std::min(low[p], low[v]);
      subtree[p] += subtree[v];
      if (low[v] > order[p]) bridge_children.push_back(v);
    }
  }
  std::vector<bool> is_bridge_child(n, false);
  for (const int v : bridge_children) {
    const int other_side = part_size[part_of[v]] - subtree[v];
    if (std::min(subtree[v], other_side) >= min_side) is_bridge_child[v] = true;
  }
  std::vector<WeightedEdge> bridges;
  for (const WeightedEdge& e : graph.Edges()) {
    if ((is_bridge_child[e.v] && parent[e.v] == e.u) ||
        (is_bridge_child[e.u] && parent[e.u] == e.v)) {
      bridges.push_back({std::min(e.u, e.v), std::max(e.u, e.v), e.weight});
    }
  }
  return bridges;
}

ImageGraph BuildDifferenceGraph(const ImageGraph& similarity_graph) {
  std::vector<WeightedEdge> edges = similarity_graph.Edges();
  for (WeightedEdge& e : edges) e.weight = 1.0 - e.weight;
  return ImageGraph(similarity_graph.NumVertices(), std::move(edges));
}

}  // namespace tmr
