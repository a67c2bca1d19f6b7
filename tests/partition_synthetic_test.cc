// Copyright (c) 2026, the tmr authors. BSD-3-Clause.
// The TMR-tree of tmr_synth scenes with several dense places, linked,
// weakly linked and unlinked: every place gets its own kernel and at least
// 90% of its images land in the clusters of its kernels.
#include <gtest/gtest.h>

#include <filesystem>
#include <map>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "tmr/colmap/synthetic_scene.h"
#include "tmr/io/database_reader.h"
#include "tmr/partition/tmr_tree.h"

namespace tmr {
namespace {

namespace fs = std::filesystem;

std::string Part(const std::string& name) {
  return name.substr(0, name.find('/'));
}

// Writes the scene into `dir` (removed again) and partitions it with the
// default options.
TmrTree PartitionScene(const SyntheticSceneOptions& options,
                       const fs::path& dir) {
  fs::remove_all(dir);
  std::string error;
  EXPECT_TRUE(WriteSyntheticScene(options, (dir / "database.db").string(), "",
                                  nullptr, &error))
      << error;
  const MatchGraph graph = ReadMatchGraph((dir / "database.db").string());
  fs::remove_all(dir);
  return BuildTmrTree(graph, {});
}

// The place of a kernel, the part most of its images come from, and how
// many of them do.
std::pair<std::string, int> PlaceOfKernel(const TmrTree& tree,
                                          const TmrKernelNode& node) {
  std::map<std::string, int> votes;
  for (const int v : node.kernel_images) ++votes[Part(tree.image_names[v])];
  return *std::max_element(
      votes.begin(), votes.end(),
      [](const auto& a, const auto& b) { return a.second < b.second; });
}

class PartitionSyntheticTest : public ::testing::TestWithParam<double> {};

TEST_P(PartitionSyntheticTest, EveryPlaceGetsItsKernelAndItsImages) {
  const fs::path dir =
      fs::temp_directory_path() /
      ("tmr_partition_synth_" + std::to_string(static_cast<int>(GetParam())));
  SyntheticSceneOptions options;
  options.num_places = 3;
  options.num_unlinked_places = 1;
  options.link_spacing = GetParam();
  options.seed = 11;
  const TmrTree tree = PartitionScene(options, dir);

  // The place of a kernel: the part most of its images come from.
  std::map<std::string, int> images_of_place;
  for (const auto& name : tree.image_names) {
    if (Part(name).rfind("place", 0) == 0) ++images_of_place[Part(name)];
  }
  ASSERT_EQ(images_of_place.size(), 4u);
  std::map<std::string, int> kernels_of_place, clustered_in_own;
  for (const TmrKernelNode& node : tree.kernels) {
    const auto best = PlaceOfKernel(tree, node);
    EXPECT_GE(best.second, 0.8 * node.kernel_images.size())
        << "a kernel mixes places";
    ++kernels_of_place[best.first];
    for (const int v : node.cluster_images) {
      if (Part(tree.image_names[v]) == best.first)
        ++clustered_in_own[best.first];
    }
  }
  for (const auto& [place, count] : images_of_place) {
    EXPECT_GE(kernels_of_place[place], 1) << place << " has no kernel";
    EXPECT_GE(clustered_in_own[place], 0.9 * count) << place;
  }
}

INSTANTIATE_TEST_SUITE_P(LinkSpacing, PartitionSyntheticTest,
                         ::testing::Values(3.0, 9.0, 0.0));

// The row of an image of a `place_rows` scene: that of its place, or of the
// first place of its link ("link3-4").
int RowOf(const std::string& part, const std::vector<int>& rows) {
  const size_t digits = part.find_first_of("0123456789");
  const int place = std::stoi(part.substr(digits));
  int first = 0;
  for (size_t r = 0; r < rows.size(); ++r) {
    if (place < first + rows[r]) return static_cast<int>(r);
    first += rows[r];
  }
  return -1;
}

// Dense places of 40 to 200 photos chained by corridors of several lengths,
// in two rows that only false pairs link: every place has its own
// kernel of at least the floor, its kernels' clusters hold its photos and
// few of other places', and no cluster reaches across the rows.
TEST(PartitionSynthetic, PlacesOfEverySizeInTwoRows) {
  SyntheticSceneOptions options;
  options.place_cameras = "40,90,200,60,120";
  options.place_rows = "3,2";
  options.vary_link_lengths = true;
  options.num_unlinked_places = 0;
  options.link_spacing = 6.0;
  options.false_pairs_per_100_images = 2.0;
  options.seed = 5;
  const TmrTree tree =
      PartitionScene(options, fs::temp_directory_path() / "tmr_partition_rows");
  const std::vector<int> rows = options.PlaceRows();

  std::map<std::string, int> kernels_of_place;
  for (const TmrKernelNode& node : tree.kernels) {
    // Below the floor only a connected part of its own (a piece of
    // corridor cut off by the varied link lengths): nothing hangs on it.
    if (static_cast<int>(node.kernel_images.size()) <
        tree.options.kernels.kernel_size_floor) {
      EXPECT_EQ(node.origin, KernelOrigin::kRescue);
      EXPECT_EQ(node.cluster_images, node.kernel_images);
      EXPECT_EQ(Part(tree.image_names[node.exemplar]).rfind("link", 0), 0u);
      continue;
    }
    const std::string place = PlaceOfKernel(tree, node).first;
    ++kernels_of_place[place];
    // Purity: of the cluster's place photos, those of the kernel's place.
    int place_photos = 0, own = 0;
    std::set<int> cluster_rows;
    for (const int v : node.cluster_images) {
      const std::string part = Part(tree.image_names[v]);
      cluster_rows.insert(RowOf(part, rows));
      if (part.rfind("place", 0) != 0) continue;
      ++place_photos;
      own += part == place;
    }
    EXPECT_GE(own, 0.9 * place_photos) << "the cluster of " << place;
    EXPECT_EQ(cluster_rows.size(), 1u) << "the cluster of " << place;
  }
  for (int p = 0; p < 5; ++p)
    EXPECT_GE(kernels_of_place["place" + std::to_string(p)], 1) << p;
}

}  // namespace
}  // namespace tmr
