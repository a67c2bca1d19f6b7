// Copyright (c) 2026, the tmr authors. BSD-3-Clause.
#include "tmr/partition/image_clustering.h"

#include <algorithm>
#include <boost/graph/compressed_sparse_row_graph.hpp>
#include <boost/graph/dijkstra_shortest_paths.hpp>
#include <boost/graph/filtered_graph.hpp>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <utility>

namespace tmr {
namespace {

struct EdgeWeight {
  double weight;
};
using CsrGraph =
    boost::compressed_sparse_row_graph<boost::directedS, boost::no_property,
                                       EdgeWeight>;
using Edge = boost::graph_traits<CsrGraph>::edge_descriptor;

// Keeps the edges whose weight is below the layer's threshold.
struct BelowThreshold {
  const CsrGraph* graph = nullptr;
  double threshold = 0.0;
  bool inclusive = false;
  bool operator()(const Edge& e) const {
    const double w = (*graph)[e].weight;
    return inclusive ? w <= threshold : w < threshold;
  }
};

// D as a Boost.Graph CSR graph, without the single-pair links between two
// groups of at least `min_side` images (none left out for 0) but for those
// inside a kernel (its exemplar reaches all its images). kernel_of: kernel
// of each image, -1 for none.
CsrGraph ToCsrWithoutBridges(const ImageGraph& graph, int min_side,
                             const std::vector<int>& kernel_of) {
  const std::vector<WeightedEdge> bridges =
      min_side > 0 ? FindBridges(graph, min_side) : std::vector<WeightedEdge>();
  std::vector<std::pair<int, int>> edges;
  std::vector<EdgeWeight> weights;
  edges.reserve(2 * graph.NumEdges());
  weights.reserve(2 * graph.NumEdges());
  size_t b = 0;  // bridges come in edge-list order
  for (const WeightedEdge& e : graph.Edges()) {
    if (b < bridges.size() && std::min(e.u, e.v) == bridges[b].u &&
        std::max(e.u, e.v) == bridges[b].v) {
      ++b;
      if (kernel_of[e.u] < 0 || kernel_of[e.u] != kernel_of[e.v]) continue;
    }
    edges.emplace_back(e.u, e.v);
    edges.emplace_back(e.v, e.u);
    weights.push_back({e.weight});
    weights.push_back({e.weight});
  }
  return CsrGraph(boost::edges_are_unsorted_multi_pass, edges.begin(),
                  edges.end(), weights.begin(), graph.NumVertices());
}

}  // namespace

void MultiLayerShortestPathOptions::AddTo(OptionTable* t) {
  t->Add("Tmr.msp_layers", &num_layers,
         "layers L of the Multi-layer Shortest Path")
      .AtLeast(1);
  t->Add("Tmr.min_bridge_side", &min_bridge_side,
         "a single pair linking two groups of at least this many images never "
         "pulls one into the other's cluster (0: the paper)")
      .AtLeast(0);
}

bool MultiLayerShortestPathOptions::Check(std::string* error) const {
  return CheckOptionRows(*this, error);
}

ImageClusters AssignByMultiLayerShortestPath(
    const ImageGraph& difference, const std::vector<std::vector<int>>& kernels,
    const std::vector<int>& exemplars,
    const MultiLayerShortestPathOptions& options) {
  std::string error;
  if (!options.Check(&error))
    throw std::invalid_argument("MultiLayerShortestPath: " + error);
  if (kernels.size() != exemplars.size()) {
    throw std::invalid_argument(
        "AssignByMultiLayerShortestPath: one exemplar per kernel");
  }
  const int n = difference.NumVertices();
  ImageClusters result;
  result.cluster.assign(n, -1);
  result.layer.assign(n, 0);
  result.path_length.assign(n, std::numeric_limits<double>::infinity());
  for (size_t k = 0; k < kernels.size(); ++k) {
    for (const int v : kernels[k]) result.cluster.at(v) = static_cast<int>(k);
  }
  if (exemplars.empty() || difference.NumEdges() == 0) return result;

  const CsrGraph graph =
      ToCsrWithoutBridges(difference, options.min_bridge_side, result.cluster);
  const double min_d = difference.MinWeight();
  const double step = (difference.MaxWeight() - min_d) / options.num_layers;
  std::vector<double> distance(n);
  std::vector<int> predecessor(n);
  auto index = boost::get(boost::vertex_index, graph);
  for (int t = 1; t <= options.num_layers; ++t) {
    const bool last = t == options.num_layers;
    const BelowThreshold keep{
        &graph, last ? difference.MaxWeight() : min_d + t * step, last};
    const boost::filtered_graph<CsrGraph, BelowThreshold> layer(graph, keep);
    boost::dijkstra_shortest_paths(
        layer, exemplars.begin(), exemplars.end(),
        boost::make_iterator_property_map(predecessor.begin(), index),
        boost::make_iterator_property_map(distance.begin(), index),
        boost::get(&EdgeWeight::weight, graph), index, std::less<double>(),
        boost::closed_plus<double>(), std::numeric_limits<double>::infinity(),
        0.0, boost::default_dijkstra_visitor());
    // The cluster of the first clustered image on the path back to the
    // exemplar: a path may pass through another cluster's images (a kernel
    // image far from its exemplar, an image assigned in an earlier layer),
    // and the images beyond such an image join its cluster, so that every
    // cluster stays connected through its own images (a leaf task can only
    // register images it reaches from the kernel).
    std::vector<int> reached_from(n, -2);
    auto origin = [&](int v) {
      std::vector<int> chain;
      while (reached_from[v] == -2 && result.cluster[v] < 0 &&
             predecessor[v] != v) {
        chain.push_back(v);
        v = predecessor[v];
      }
      const int label =
          reached_from[v] != -2 ? reached_from[v] : result.cluster[v];
      for (const int u : chain) reached_from[u] = label;
      reached_from[v] = label;
      return label;
    };
    for (int v = 0; v < n; ++v) {
      if (distance[v] == std::numeric_limits<double>::infinity()) continue;
      if (result.cluster[v] >= 0) {  // a kernel image or assigned earlier
        if (result.layer[v] == 0 && result.path_length[v] == INFINITY) {
          result.path_length[v] = distance[v];
        }
        continue;
      }
      result.cluster[v] = origin(v);
      result.layer[v] = t;
      result.path_length[v] = distance[v];
    }
  }
  for (const int e : exemplars) result.path_length[e] = 0.0;
  return result;
}

}  // namespace tmr
