// Copyright (c) 2026, the tmr authors. BSD-3-Clause.
#pragma once

#include <utility>
#include <vector>

#include "tmr/scene/match_graph.h"

namespace tmr {

struct WeightedEdge {
  int u = 0;
  int v = 0;
  double weight = 0.0;
};

// An undirected weighted graph on image indices 0..n-1 (the indices of
// MatchGraph::images), stored as an edge list plus a compressed adjacency
// list. Used for both the similarity graph S and the difference graph D of
// the paper (Sec. 3): they share vertices and edges and differ in weights.
class ImageGraph {
 public:
  struct Neighbor {
    int vertex;
    double weight;
  };

  ImageGraph() = default;
  // Throws std::invalid_argument for an endpoint out of range, a self loop or
  // a duplicate edge.
  ImageGraph(int num_vertices, std::vector<WeightedEdge> edges);

  int NumVertices() const { return num_vertices_; }
  int NumEdges() const { return static_cast<int>(edges_.size()); }
  const std::vector<WeightedEdge>& Edges() const { return edges_; }

  // Neighbours of v as a [begin, end) range.
  std::pair<const Neighbor*, const Neighbor*> Neighbors(int v) const;
  int Degree(int v) const;
  // Weight of edge (u, v), or `missing` when there is no such edge.
  double Weight(int u, int v, double missing = 0.0) const;

  // Smallest and largest edge weight; both 0 for a graph without edges.
  double MinWeight() const;
  double MaxWeight() const;

 private:
  int num_vertices_ = 0;
  std::vector<WeightedEdge> edges_;
  std::vector<int> offsets_;  // size num_vertices_ + 1
  std::vector<Neighbor> adjacency_;
};

// Similarity graph S (paper Eq. 1): for every pair of the match graph,
// s_ij = n_ij / |n_i ∪ n_j| = n_ij / (n_i + n_j - n_ij), the Jaccard
// coefficient of the two images' matched keypoint sets. The denominator is
// clamped to at least n_ij so that s_ij stays in (0, 1] even for pairs whose
// inlier list repeats a keypoint.
ImageGraph BuildSimilarityGraph(const MatchGraph& match_graph);

// Difference graph D (paper Eq. 2): the same edges with d_ij = 1 - s_ij.
ImageGraph BuildDifferenceGraph(const ImageGraph& similarity_graph);

// The bridges of the graph (edges whose removal splits their connected
// part: the only pair that links two groups of images) that leave at least
// `min_side` images on each side, by Tarjan's low-link depth-first search
// (iterative, O(V + E)). Each edge is given with u < v, in edge-list order.
std::vector<WeightedEdge> FindBridges(const ImageGraph& graph, int min_side);

}  // namespace tmr
