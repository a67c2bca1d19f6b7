// Copyright (c) 2026, the tmr authors. BSD-3-Clause.
#include "tmr/partition/merge_groups.h"

#include <algorithm>
#include <functional>
#include <limits>
#include <map>
#include <numeric>
#include <queue>
#include <tuple>
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

namespace {

using Neighbours = std::vector<std::vector<std::pair<int, int64_t>>>;
constexpr int kUnreached = std::numeric_limits<int>::max();

// Links between clusters from `source`, over the clusters `open` allows
// (kUnreached where none leads).
std::vector<int> Hops(const Neighbours& neighbours, int source,
                      const std::vector<bool>& open) {
  std::vector<int> hops(neighbours.size(), kUnreached);
  std::queue<int> queue;
  hops[source] = 0;
  queue.push(source);
  while (!queue.empty()) {
    const int c = queue.front();
    queue.pop();
    for (const auto& [other, matches] : neighbours[c]) {
      if (!open[other] || hops[other] != kUnreached) continue;
      hops[other] = hops[c] + 1;
      queue.push(other);
    }
  }
  return hops;
}

// The reached cluster with the most hops (the smallest on a tie).
int Farthest(const std::vector<int>& hops) {
  int farthest = -1;
  for (int c = 0; c < static_cast<int>(hops.size()); ++c) {
    if (hops[c] != kUnreached && (farthest < 0 || hops[c] > hops[farthest]))
      farthest = c;
  }
  return farthest;
}

}  // namespace

std::vector<std::vector<int>> GroupClusters(
    const std::vector<double>& cost, const std::vector<ClusterLink>& links,
    double max_cost,
    const std::function<double(const std::vector<int>&)>& group_cost) {
  const int n = static_cast<int>(cost.size());
  if (n == 0) return {};
  Neighbours neighbours(n);
  for (const ClusterLink& link : links) {
    neighbours.at(link.cluster1).emplace_back(link.cluster2, link.num_matches);
    neighbours.at(link.cluster2).emplace_back(link.cluster1, link.num_matches);
  }
  // The sweep's origin: a peripheral cluster, the farthest from the
  // costliest one.
  const std::vector<bool> all(n, true);
  const int costliest = static_cast<int>(
      std::max_element(cost.begin(), cost.end()) - cost.begin());
  const std::vector<int> from_origin =
      Hops(neighbours, Farthest(Hops(neighbours, costliest, all)), all);
  std::vector<int> seeds(n);
  std::iota(seeds.begin(), seeds.end(), 0);
  std::stable_sort(seeds.begin(), seeds.end(), [&](int a, int b) {
    return from_origin[a] < from_origin[b];
  });
  std::vector<bool> grouped(n, false);
  std::vector<std::vector<int>> groups;
  for (const int seed : seeds) {
    if (grouped[seed]) continue;
    std::vector<bool> open(n);
    for (int c = 0; c < n; ++c) open[c] = !grouped[c];
    const std::vector<int> from_seed = Hops(neighbours, seed, open);
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
      // The ungrouped clusters next to the group, the nearest to the seed
      // first, then those with the most matches into the group.
      std::vector<std::tuple<int, int64_t, int>> order;
      for (const auto& [c, m] : into) order.emplace_back(from_seed[c], -m, c);
      std::sort(order.begin(), order.end());
      int best = -1;
      for (const auto& [hops, minus_matches, c] : order) {
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
