// Copyright (c) 2026, the tmr authors. BSD-3-Clause.
#pragma once

#include <cstdint>
#include <functional>
#include <vector>

#include "tmr/scene/match_graph.h"

namespace tmr {

// The verified matches between two image clusters: n_ij (Eq. 1) summed
// over the pairs with one image in each. cluster1 < cluster2.
struct ClusterLink {
  int cluster1 = 0;
  int cluster2 = 0;
  int64_t num_matches = 0;
};

// Every pair of clusters that verified pairs link, sorted by (cluster1,
// cluster2). `cluster_of` gives each image's cluster (-1: none).
std::vector<ClusterLink> LinkClusters(const MatchGraph& graph,
                                      const std::vector<int>& cluster_of);

// Groups of image clusters for the merge stage by parts: each group is
// merged on its own, within a memory budget, and the groups are then
// joined. Greedy graph growing on the cluster graph, in compact balls: the
// ungrouped cluster nearest (in links) to a peripheral origin (the cluster
// farthest from the costliest) seeds a group, which takes, one at a time,
// the ungrouped cluster next to it that is nearest to its seed (the most
// verified matches into the group first among equals) and still fits
// `max_cost`, until none does. Growing by the strongest links alone made
// groups that interleave: in a city, the photos of the north and of the
// south facades formed two groups, each over the whole city, each less
// accurate than the whole (docs/distributed.md). A group is connected; a
// cluster costlier than `max_cost` is a group alone. Each group is sorted,
// groups in the order they were seeded. Deterministic (ties go to the
// smaller index). `group_cost`, when given, is the cost of a group as a
// whole, for costs that do not add up (clusters that share images, a fixed
// cost per group): the fit test then uses it.
std::vector<std::vector<int>> GroupClusters(
    const std::vector<double>& cost, const std::vector<ClusterLink>& links,
    double max_cost,
    const std::function<double(const std::vector<int>&)>& group_cost = {});

}  // namespace tmr
