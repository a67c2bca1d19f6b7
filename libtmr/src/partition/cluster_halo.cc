// Copyright (c) 2026, the tmr authors. BSD-3-Clause.
#include "tmr/partition/cluster_halo.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <stdexcept>
#include <utility>

namespace tmr {

void ClusterHaloOptions::AddTo(OptionTable* t) {
  t->Add("Tmr.halo_images", &images_per_neighbour,
         "images a cluster's tasks also register from each neighbouring "
         "cluster (0: none)")
      .AtLeast(0);
  t->Add("Tmr.halo_min_matches", &min_matches,
         "verified matches a halo image has into the cluster")
      .AtLeast(1);
  t->Add("Tmr.halo_max_share", &max_share,
         "largest halo as a share of its cluster's images")
      .AtLeast(0);
}

bool ClusterHaloOptions::Check(std::string* error) const {
  return CheckOptionRows(*this, error);
}

std::vector<std::vector<int>> FindClusterHalos(
    const MatchGraph& graph, const std::vector<int>& cluster_of,
    int num_clusters, const ClusterHaloOptions& options) {
  std::string error;
  if (!options.Check(&error))
    throw std::invalid_argument("ClusterHaloOptions: " + error);
  if (static_cast<int>(cluster_of.size()) != graph.NumImages())
    throw std::invalid_argument("FindClusterHalos: one cluster per image");
  std::vector<std::vector<int>> halos(num_clusters);
  if (options.images_per_neighbour == 0) return halos;
  // weight[c][j]: verified matches of image j (outside c) into cluster c.
  std::vector<std::map<int, long>> weight(num_clusters);
  std::vector<int> size(num_clusters, 0);
  for (const int c : cluster_of) {
    if (c >= num_clusters) throw std::invalid_argument("cluster out of range");
    if (c >= 0) ++size[c];
  }
  for (const MatchGraphPair& pair : graph.pairs) {
    const int c1 = cluster_of[pair.image1], c2 = cluster_of[pair.image2];
    if (c1 < 0 || c2 < 0 || c1 == c2) continue;
    weight[c1][pair.image2] += pair.num_inliers;
    weight[c2][pair.image1] += pair.num_inliers;
  }
  for (int c = 0; c < num_clusters; ++c) {
    // The best images of every neighbour, then the strongest of those.
    std::map<int, std::vector<std::pair<long, int>>> by_neighbour;
    for (const auto& [image, w] : weight[c]) {
      if (w >= options.min_matches)
        by_neighbour[cluster_of[image]].emplace_back(-w, image);
    }
    std::vector<std::pair<long, int>> chosen;
    for (auto& [neighbour, candidates] : by_neighbour) {
      std::sort(candidates.begin(), candidates.end());
      const size_t n =
          std::min<size_t>(candidates.size(), options.images_per_neighbour);
      chosen.insert(chosen.end(), candidates.begin(), candidates.begin() + n);
    }
    std::sort(chosen.begin(), chosen.end());
    const size_t limit =
        static_cast<size_t>(std::floor(options.max_share * size[c]));
    if (chosen.size() > limit) chosen.resize(limit);
    for (const auto& [w, image] : chosen) halos[c].push_back(image);
    std::sort(halos[c].begin(), halos[c].end());
  }
  return halos;
}

std::vector<std::vector<int>> AssignHaloToLeaves(
    const MatchGraph& graph, const std::vector<std::vector<int>>& leaves,
    const std::vector<int>& halo) {
  std::vector<std::vector<int>> assigned(leaves.size());
  if (leaves.empty()) return assigned;
  std::map<int, int> leaf_of;
  for (size_t l = 0; l < leaves.size(); ++l)
    for (const int v : leaves[l]) leaf_of[v] = static_cast<int>(l);
  // matches[j][l]: verified matches of halo image j with leaf l's images.
  std::map<int, std::vector<long>> matches;
  for (const int j : halo) matches[j].assign(leaves.size(), 0);
  for (const MatchGraphPair& pair : graph.pairs) {
    for (const auto& [a, b] : {std::pair(pair.image1, pair.image2),
                               std::pair(pair.image2, pair.image1)}) {
      const auto j = matches.find(a);
      const auto l = leaf_of.find(b);
      if (j != matches.end() && l != leaf_of.end())
        j->second[l->second] += pair.num_inliers;
    }
  }
  for (const int j : halo) {
    const std::vector<long>& m = matches[j];
    size_t best = std::max_element(m.begin(), m.end()) - m.begin();
    if (m[best] == 0) {
      for (size_t l = 0; l < leaves.size(); ++l) {
        if (leaves[l].size() + assigned[l].size() <
            leaves[best].size() + assigned[best].size())
          best = l;
      }
    }
    assigned[best].push_back(j);
  }
  for (auto& list : assigned) std::sort(list.begin(), list.end());
  return assigned;
}

}  // namespace tmr
