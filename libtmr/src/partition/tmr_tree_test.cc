// Copyright (c) 2026, the tmr authors. BSD-3-Clause.
#include "tmr/partition/tmr_tree.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <sstream>

#include "partition/test_graphs.h"

namespace tmr {
namespace {

MatchGraph TwoGroupsWithChain() {
  const test::TwoGroups scene(18, 30, /*with_chain=*/true);
  MatchGraph graph =
      test::MatchGraphWithSimilarities(scene.num_images, scene.edges);
  graph.images.push_back({1000, "lonely.jpg", 1, 100, 0});  // no pair at all
  return graph;
}

// These graphs have groups of 18 images joined by a chain of single pairs:
// the paper's floor of 3, and its image clustering, which crosses them.
TmrTreeOptions SmallScaleOptions() {
  TmrTreeOptions options;
  options.kernels.kernel_size_floor = 3;
  options.image_clustering.min_bridge_side = 0;
  return options;
}

std::string Json(const TmrTree& tree) {
  std::ostringstream out;
  WriteTmrTreeJson(tree, out);
  return out.str();
}

TEST(TmrTree, TwoGroupsGiveTwoKernelsWithClustersAndLeaves) {
  const MatchGraph graph = TwoGroupsWithChain();
  const TmrTree tree = BuildTmrTree(graph, SmallScaleOptions());
  ASSERT_EQ(tree.kernels.size(), 2u);
  EXPECT_EQ(tree.unclustered, std::vector<int>{graph.NumImages() - 1});
  int clustered = 0;
  for (const TmrKernelNode& node : tree.kernels) {
    EXPECT_TRUE(std::binary_search(node.kernel_images.begin(),
                                   node.kernel_images.end(), node.exemplar));
    EXPECT_FALSE(node.second_images.empty());
    EXPECT_FALSE(node.leaf_clusters.empty());
    size_t leaves = 0;
    for (const auto& leaf : node.leaf_clusters) leaves += leaf.size();
    EXPECT_EQ(node.kernel_images.size() + leaves, node.cluster_images.size());
    clustered += node.cluster_images.size();
  }
  EXPECT_EQ(clustered + 1, graph.NumImages());
}

TEST(TmrTree, LeavesRegisterAHaloFromTheOtherCluster) {
  const MatchGraph graph = TwoGroupsWithChain();
  TmrTreeOptions options = SmallScaleOptions();
  options.halo.min_matches = 1;  // the chain's pairs are weak
  const TmrTree tree = BuildTmrTree(graph, options);
  ASSERT_EQ(tree.kernels.size(), 2u);
  for (int k = 0; k < 2; ++k) {
    const TmrKernelNode& node = tree.kernels[k];
    const TmrKernelNode& other = tree.kernels[1 - k];
    ASSERT_EQ(node.leaf_halos.size(), node.leaf_clusters.size());
    int num_halo = 0;
    for (const auto& halo : node.leaf_halos) {
      for (const int v : halo) {
        EXPECT_TRUE(std::binary_search(other.cluster_images.begin(),
                                       other.cluster_images.end(), v));
        ++num_halo;
      }
    }
    EXPECT_GT(num_halo, 0);
  }
  options.halo.images_per_neighbour = 0;
  for (const TmrKernelNode& node : BuildTmrTree(graph, options).kernels)
    for (const auto& halo : node.leaf_halos) EXPECT_TRUE(halo.empty());
}

TEST(TmrTree, SameSeedSameTreeAndJsonRoundTrip) {
  const MatchGraph graph = TwoGroupsWithChain();
  TmrTreeOptions options = SmallScaleOptions();
  options.seed = 17;
  options.halo.min_matches = 1;
  const TmrTree a = BuildTmrTree(graph, options);
  const TmrTree b = BuildTmrTree(graph, options);
  TmrTree a_copy = a, b_copy = b;
  a_copy.timing = b_copy.timing = TmrTreeTiming();
  EXPECT_EQ(Json(a_copy), Json(b_copy));

  std::istringstream in(Json(a));
  std::vector<std::string> names;
  for (const auto& image : graph.images) names.push_back(image.name);
  const TmrTree read = ReadTmrTreeJson(in, names);
  ASSERT_EQ(read.kernels.size(), a.kernels.size());
  for (size_t k = 0; k < a.kernels.size(); ++k) {
    EXPECT_EQ(read.kernels[k].exemplar, a.kernels[k].exemplar);
    EXPECT_EQ(read.kernels[k].second_images, a.kernels[k].second_images);
    EXPECT_EQ(read.kernels[k].kernel_images, a.kernels[k].kernel_images);
    EXPECT_EQ(read.kernels[k].leaf_clusters, a.kernels[k].leaf_clusters);
    EXPECT_EQ(read.kernels[k].leaf_halos, a.kernels[k].leaf_halos);
    EXPECT_EQ(read.kernels[k].cluster_images, a.kernels[k].cluster_images);
  }
  EXPECT_EQ(read.unclustered, a.unclustered);
  EXPECT_EQ(read.kernel_size, a.kernel_size);
  EXPECT_EQ(read.options.seed, 17u);
  EXPECT_EQ(read.options.leaf_clustering.sigma3, 3.0);
}

TEST(TmrTree, JsonHasTheDocumentedFields) {
  const std::string json =
      Json(BuildTmrTree(TwoGroupsWithChain(), SmallScaleOptions()));
  for (const char* field :
       {"\"exemplar\"", "\"second_image\"", "\"kernel_images\"",
        "\"leaf_clusters\"", "\"unclustered\"", "\"parameters\""}) {
    EXPECT_NE(json.find(field), std::string::npos) << field;
  }
}

TEST(TmrTree, MalformedJsonIsAClearError) {
  for (const std::string text :
       {"", "{", "[]", "{\"format\": \"other\"}", "{\"format\": \"tmr-tree\"}",
        "{\"format\": \"tmr-tree\", \"kernels\": [{\"exemplar\": 5}], "
        "\"unclustered\": []}",
        "{\"format\": \"tmr-tree\", \"kernels\": [], \"unclustered\": "
        "[\"x\"]}",
        // Integers out of range or with a fraction (found by fuzzing).
        "{\"format\": \"tmr-tree\", \"kernel_size\": 3e41, \"kernels\": [], "
        "\"unclustered\": []}",
        "{\"format\": \"tmr-tree\", \"kernel_size\": 2.5, \"kernels\": [], "
        "\"unclustered\": []}",
        "{\"format\": \"tmr-tree\", \"parameters\": {\"Tmr.seed\": -1}, "
        "\"kernels\": [], \"unclustered\": []}"}) {
    std::istringstream in(text);
    EXPECT_THROW(ReadTmrTreeJson(in, {"a", "b"}), std::runtime_error) << text;
  }
}

TEST(TmrTree, EmptyGraph) {
  const TmrTree tree = BuildTmrTree(MatchGraph(), {});
  EXPECT_TRUE(tree.kernels.empty());
  EXPECT_TRUE(tree.unclustered.empty());
}

}  // namespace
}  // namespace tmr
