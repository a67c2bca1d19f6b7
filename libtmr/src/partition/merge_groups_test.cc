// Copyright (c) 2026, the tmr authors. BSD-3-Clause.
#include "tmr/partition/merge_groups.h"

#include <gtest/gtest.h>

#include <algorithm>

namespace tmr {
namespace {

// Images 0..5 in clusters 0, 0, 1, 1, 2, -1.
MatchGraph SixImages() {
  MatchGraph graph;
  for (int i = 0; i < 6; ++i) graph.images.push_back({uint32_t(i + 1)});
  graph.pairs = {{0, 1, 500}, {0, 2, 40}, {1, 3, 60}, {2, 4, 30},
                 {3, 4, 5},   {4, 5, 90}, {0, 5, 70}};
  return graph;
}

TEST(MergeGroups, LinksSumTheMatchesBetweenClusters) {
  const std::vector<ClusterLink> links =
      LinkClusters(SixImages(), {0, 0, 1, 1, 2, -1});
  ASSERT_EQ(links.size(), 2u);
  EXPECT_EQ(links[0].cluster1, 0);
  EXPECT_EQ(links[0].cluster2, 1);
  EXPECT_EQ(links[0].num_matches, 100);
  EXPECT_EQ(links[1].cluster1, 1);
  EXPECT_EQ(links[1].cluster2, 2);
  EXPECT_EQ(links[1].num_matches, 35);
}

TEST(MergeGroups, EverythingInOneGroupWhenItFits) {
  const auto groups = GroupClusters({1, 2, 3}, {{0, 1, 10}, {1, 2, 5}}, 10);
  EXPECT_EQ(groups, (std::vector<std::vector<int>>{{0, 1, 2}}));
}

TEST(MergeGroups, AChainIsCutWhereTheBudgetEnds) {
  // A chain 0 - 1 - 2 - 3 - 4 - 5: grown from its end, two groups of three.
  const std::vector<ClusterLink> links = {
      {0, 1, 900}, {1, 2, 800}, {2, 3, 10}, {3, 4, 700}, {4, 5, 600}};
  const auto groups = GroupClusters({1, 1, 1, 1.5, 1, 1}, links, 3.5);
  EXPECT_EQ(groups, (std::vector<std::vector<int>>{{0, 1, 2}, {3, 4, 5}}));
}

TEST(MergeGroups, GroupsArePlacesNotSheets) {
  // Two rows of clusters over the same places (as the photos of a street's
  // north and south facades): strong links along each row (clusters i and
  // i + 1), weak ones across (clusters i and 6 + i). Each group holds both
  // rows of half of the places, not one row of all of them.
  std::vector<ClusterLink> links;
  for (int i = 0; i < 6; ++i) {
    if (i < 5) links.push_back({i, i + 1, 900});
    if (i < 5) links.push_back({6 + i, 7 + i, 900});
    links.push_back({i, 6 + i, 10});
  }
  std::sort(links.begin(), links.end(), [](const auto& a, const auto& b) {
    return std::make_pair(a.cluster1, a.cluster2) <
           std::make_pair(b.cluster1, b.cluster2);
  });
  const auto groups = GroupClusters(std::vector<double>(12, 1), links, 6);
  EXPECT_EQ(groups, (std::vector<std::vector<int>>{{3, 4, 5, 9, 10, 11},
                                                   {0, 1, 2, 6, 7, 8}}));
}

TEST(MergeGroups, AGroupCostThatDoesNotAddUpDecidesWhatFits) {
  // Each cluster alone costs 5, of which 2 are a fixed cost that a group
  // pays once: three clusters need 2 + 3 * 3 = 11, not 15.
  const std::vector<ClusterLink> links = {{0, 1, 10}, {1, 2, 5}};
  EXPECT_EQ(GroupClusters({5, 5, 5}, links, 11),
            (std::vector<std::vector<int>>{{1, 2}, {0}}));
  const auto group_cost = [](const std::vector<int>& group) {
    return 2.0 + 3.0 * group.size();
  };
  EXPECT_EQ(GroupClusters({5, 5, 5}, links, 11, group_cost),
            (std::vector<std::vector<int>>{{0, 1, 2}}));
}

TEST(MergeGroups, TheOriginIsFoundInTheCostliestClustersPart) {
  // Cluster 0 alone; the chain 1 - 2 - 3 - 4 holds the costliest (3): the
  // sweep starts at its far end, 1, not at the unlinked cluster 0.
  const std::vector<ClusterLink> links = {
      {1, 2, 100}, {2, 3, 100}, {3, 4, 100}};
  EXPECT_EQ(GroupClusters({1, 1, 1, 2, 1}, links, 2.5),
            (std::vector<std::vector<int>>{{1, 2}, {3}, {4}, {0}}));
}

TEST(MergeGroups, EveryClusterInExactlyOneGroupWithinTheBudget) {
  std::vector<double> cost;
  std::vector<ClusterLink> links;
  for (int c = 0; c < 40; ++c) {
    cost.push_back(1 + c % 4);
    if (c > 0) links.push_back({c - 1, c, 100 + (c * 37) % 50});
    if (c > 7) links.push_back({c - 8, c, 50});
  }
  cost[5] = 20;  // above the budget: a group of its own
  const auto groups = GroupClusters(cost, links, 10);
  std::vector<int> seen(cost.size(), 0);
  for (const auto& group : groups) {
    double total = 0;
    for (const int c : group) {
      ++seen[c];
      total += cost[c];
    }
    if (group.size() > 1) EXPECT_LE(total, 10);
  }
  for (const int s : seen) EXPECT_EQ(s, 1);
  for (const auto& group : groups) {
    if (std::count(group.begin(), group.end(), 5))
      EXPECT_EQ(group, std::vector<int>{5});
  }
  // Deterministic.
  EXPECT_EQ(GroupClusters(cost, links, 10), groups);
}

}  // namespace
}  // namespace tmr
