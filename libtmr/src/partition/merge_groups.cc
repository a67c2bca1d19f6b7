// Copyright (c) 2026, the tmr authors. BSD-3-Clause.
#include "tmr/partition/merge_groups.h"

#include <algorithm>
#include <functional>
#include <map>
#include <numeric>
#include <utility>

namespace tmr {

std::vector<ClusterLink> LinkClusters(const MatchGraph& graph,
                                      const std::vector<int>& cluster_of) {
  std::map<std::pair<int, int>, int64_t> matches;
  for (const MatchGraphPair& pair : graph.pairs) {
    const int a = cluster_of.at(pair.image1);
    const int b = cluster_of.at(pair.image2);
    if (a < 0 || b < 0 || a == b) continue;
    matches[{std::min(a, b), std::max(a, b)}] += pair.num_inliers;
  }
  std::vector<ClusterLink> links;
  for (const auto& [clusters, n] : matches)
    links.push_back({clusters.first, clusters.second, n});
  return links;
}

std::vector<std::vector<int>> GroupClusters(
    const std::vector<double>& cost, const std::vector<ClusterLink>& links,
    double max_cost,
    const std::function<double(const std::vector<int>&)>& group_cost) {
  const int n = static_cast<int>(cost.size());
  std::vector<std::vector<std::pair<int, int64_t>>> neighbours(n);
  for (const ClusterLink& link : links) {
    neighbours.at(link.cluster1).emplace_back(link.cluster2, link.num_matches);
    neighbours.at(link.cluster2).emplace_back(link.cluster1, link.num_matches);
  }
  std::vector<int> seeds(n);
  std::iota(seeds.begin(), seeds.end(), 0);
  std::stable_sort(seeds.begin(), seeds.end(),
                   [&](int a, int b) { return cost[a] > cost[b]; });
  std::vector<bool> grouped(n, false);
  std::vector<std::vector<int>> groups;
  for (const int seed : seeds) {
    if (grouped[seed]) continue;
    std::vector<int> group = {seed};
    grouped[seed] = true;
    double total = cost[seed];
    // Verified matches of each ungrouped cluster into the group.
    std::map<int, int64_t> into;
    auto take = [&](int c) {
      for (const auto& [other, m] : neighbours[c])
        if (!grouped[other]) into[other] += m;
      into.erase(c);
    };
    take(seed);
    // Whether the group with cluster c still fits.
    auto fits = [&](int c) {
      if (!group_cost) return total + cost[c] <= max_cost;
      std::vector<int> grown = group;
      grown.push_back(c);
      return group_cost(grown) <= max_cost;
    };
    while (true) {
      // The ungrouped clusters, most matches into the group first.
      std::vector<std::pair<int64_t, int>> order;
      for (const auto& [c, m] : into) order.emplace_back(-m, c);
      std::sort(order.begin(), order.end());
      int best = -1;
      for (const auto& [minus_matches, c] : order) {
        if (fits(c)) {
          best = c;
          break;
        }
      }
      if (best < 0) break;
      group.push_back(best);
      grouped[best] = true;
      total += cost[best];
      take(best);
    }
    std::sort(group.begin(), group.end());
    groups.push_back(std::move(group));
  }
  return groups;
}

}  // namespace tmr
