// Copyright (c) 2026, the tmr authors. BSD-3-Clause.
#include "tmr/partition/tmr_tree.h"

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <iterator>
#include <map>
#include <stdexcept>
#include <string>

#include "tmr/scene/image_graph.h"
#include "tmr/util/process.h"

namespace tmr {
void TmrTreeOptions::AddTo(OptionTable* t) {
  t->Add("Tmr.seed", &seed, "seed of every random choice");
  kernels.AddTo(t);
  exemplar.AddTo(t);
  image_clustering.AddTo(t);
  leaf_clustering.AddTo(t);
  halo.AddTo(t);
}

bool TmrTreeOptions::Check(std::string* error) const {
  return kernels.Check(error) && exemplar.Check(error) &&
         image_clustering.Check(error) && leaf_clustering.Check(error) &&
         halo.Check(error);
}

TmrTree BuildTmrTree(const MatchGraph& match_graph,
                     const TmrTreeOptions& options) {
  std::string error;
  if (!options.Check(&error))
    throw std::invalid_argument("TmrTreeOptions: " + error);
  TmrTree tree;
  tree.options = options;
  tree.options.exemplar.ap.seed = options.seed;
  for (const MatchGraphImage& image : match_graph.images) {
    tree.image_names.push_back(image.name);
    tree.image_ids.push_back(image.image_id);
  }
  tree.kernel_size = options.kernels.KernelSize(match_graph.NumImages());

  auto start = std::chrono::steady_clock::now();
  const ImageGraph s = BuildSimilarityGraph(match_graph);
  const ImageGraph d = BuildDifferenceGraph(s);
  tree.timing.graphs_s = SecondsSince(start);

  start = std::chrono::steady_clock::now();
  const std::vector<Kernel> kernels = FindKernels(s, options.kernels);
  tree.timing.kernels_s = SecondsSince(start);

  start = std::chrono::steady_clock::now();
  std::vector<std::vector<int>> kernel_images;
  std::vector<int> exemplars;
  for (const Kernel& kernel : kernels) {
    const KernelSeed seed =
        SelectExemplar(s, match_graph, kernel.images, tree.options.exemplar);
    TmrKernelNode node;
    node.kernel_images = kernel.images;
    node.exemplar = seed.exemplar;
    node.second_images = seed.second_images;
    node.ap_centres = seed.ap_centres;
    node.exemplar_score = seed.score;
    node.origin = kernel.origin;
    node.layer = kernel.layer;
    tree.kernels.push_back(std::move(node));
    kernel_images.push_back(kernel.images);
    exemplars.push_back(seed.exemplar);
  }
  tree.timing.exemplars_s = SecondsSince(start);

  start = std::chrono::steady_clock::now();
  const ImageClusters clusters = AssignByMultiLayerShortestPath(
      d, kernel_images, exemplars, options.image_clustering);
  for (int v = 0; v < match_graph.NumImages(); ++v) {
    if (clusters.cluster[v] < 0) {
      tree.unclustered.push_back(v);
    } else {
      tree.kernels[clusters.cluster[v]].cluster_images.push_back(v);
    }
  }
  tree.timing.image_clusters_s = SecondsSince(start);

  start = std::chrono::steady_clock::now();
  for (TmrKernelNode& node : tree.kernels) {
    std::vector<int> leaves;
    std::set_difference(node.cluster_images.begin(), node.cluster_images.end(),
                        node.kernel_images.begin(), node.kernel_images.end(),
                        std::back_inserter(leaves));
    node.leaf_clusters =
        RadialAgglomerateClustering(d, node.kernel_images, leaves,
                                    tree.kernel_size, options.leaf_clustering);
  }
  tree.timing.leaf_clusters_s = SecondsSince(start);

  start = std::chrono::steady_clock::now();
  const std::vector<std::vector<int>> halos =
      FindClusterHalos(match_graph, clusters.cluster,
                       static_cast<int>(tree.kernels.size()), options.halo);
  for (size_t k = 0; k < tree.kernels.size(); ++k) {
    TmrKernelNode& node = tree.kernels[k];
    node.leaf_halos =
        AssignHaloToLeaves(match_graph, node.leaf_clusters, halos[k]);
  }
  tree.timing.halos_s = SecondsSince(start);
  return tree;
}

std::vector<uint32_t> ImageIdsOf(const TmrTree& tree,
                                 const std::vector<int>& vertices) {
  std::vector<uint32_t> ids;
  ids.reserve(vertices.size());
  for (const int v : vertices) ids.push_back(tree.image_ids.at(v));
  return ids;
}

std::string DescribeKernels(const TmrTree& tree) {
  if (tree.kernels.empty()) return "";
  std::map<std::string, int> origins;
  size_t smallest = SIZE_MAX, largest = 0;
  for (const TmrKernelNode& node : tree.kernels) {
    ++origins[KernelOriginName(node.origin)];
    smallest = std::min(smallest, node.kernel_images.size());
    largest = std::max(largest, node.kernel_images.size());
  }
  std::string text;
  for (const auto& [origin, count] : origins)
    text += (text.empty() ? "" : ", ") + std::to_string(count) + " " + origin;
  return text + "; " + std::to_string(smallest) + "-" +
         std::to_string(largest) + " images";
}

DatabasePartition PartitionDatabase(const std::string& database_path,
                                    const MatchGraphOptions& graph_options,
                                    const TmrTreeOptions& tree_options) {
  const auto start = std::chrono::steady_clock::now();
  DatabasePartition partition;
  partition.graph = ReadMatchGraph(database_path, graph_options);
  partition.read_seconds = SecondsSince(start);
  if (partition.graph.NumImages() == 0)
    throw std::runtime_error("the database has no images");
  partition.tree = BuildTmrTree(partition.graph, tree_options);
  partition.seconds = SecondsSince(start);
  return partition;
}

}  // namespace tmr
