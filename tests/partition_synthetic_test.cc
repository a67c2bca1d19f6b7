// Copyright (c) 2026, the tmr authors. BSD-3-Clause.
// The TMR-tree of tmr_synth scenes with several dense places, linked,
// weakly linked and unlinked: every place gets its own kernel and at least
// 90% of its images land in the clusters of its kernels.
#include <gtest/gtest.h>

#include <filesystem>
#include <map>

#include "tmr/colmap/synthetic_scene.h"
#include "tmr/io/database_reader.h"
#include "tmr/partition/tmr_tree.h"

namespace tmr {
namespace {

namespace fs = std::filesystem;

std::string Part(const std::string& name) {
  return name.substr(0, name.find('/'));
}

class PartitionSyntheticTest : public ::testing::TestWithParam<double> {};

TEST_P(PartitionSyntheticTest, EveryPlaceGetsItsKernelAndItsImages) {
  const fs::path dir =
      fs::temp_directory_path() /
      ("tmr_partition_synth_" + std::to_string(static_cast<int>(GetParam())));
  fs::remove_all(dir);
  SyntheticSceneOptions options;
  options.num_places = 3;
  options.num_unlinked_places = 1;
  options.link_spacing = GetParam();
  options.seed = 11;
  std::string error;
  ASSERT_TRUE(WriteSyntheticScene(options, (dir / "database.db").string(), "",
                                  nullptr, &error))
      << error;
  const MatchGraph graph = ReadMatchGraph((dir / "database.db").string());
  const TmrTree tree = BuildTmrTree(graph, {});
  fs::remove_all(dir);

  // The place of a kernel: the part most of its images come from.
  std::map<std::string, int> images_of_place;
  for (const auto& name : tree.image_names) {
    if (Part(name).rfind("place", 0) == 0) ++images_of_place[Part(name)];
  }
  ASSERT_EQ(images_of_place.size(), 4u);
  std::map<std::string, int> kernels_of_place, clustered_in_own;
  for (const TmrKernelNode& node : tree.kernels) {
    std::map<std::string, int> votes;
    for (const int v : node.kernel_images) ++votes[Part(tree.image_names[v])];
    const auto best =
        std::max_element(votes.begin(), votes.end(),
                         [](auto& a, auto& b) { return a.second < b.second; });
    EXPECT_GE(best->second, 0.8 * node.kernel_images.size())
        << "a kernel mixes places";
    ++kernels_of_place[best->first];
    for (const int v : node.cluster_images) {
      if (Part(tree.image_names[v]) == best->first)
        ++clustered_in_own[best->first];
    }
  }
  for (const auto& [place, count] : images_of_place) {
    EXPECT_GE(kernels_of_place[place], 1) << place << " has no kernel";
    EXPECT_GE(clustered_in_own[place], 0.9 * count) << place;
  }
}

INSTANTIATE_TEST_SUITE_P(LinkSpacing, PartitionSyntheticTest,
                         ::testing::Values(3.0, 9.0, 0.0));

}  // namespace
}  // namespace tmr
