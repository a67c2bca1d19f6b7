// Copyright (c) 2026, the tmr authors. BSD-3-Clause.
#pragma once

#include <string>
#include <vector>

#include "tmr/scene/match_graph.h"
#include "tmr/util/option_table.h"

namespace tmr {

struct ClusterHaloOptions {
  // Images a cluster takes from each neighbouring cluster: those with the
  // most verified matches into it (COLMAP's hierarchical_mapper takes 50
  // per neighbour, its image_overlap). 0: clusters without halo.
  int images_per_neighbour = 10;
  // A halo image has at least this many verified matches (summed over its
  // pairs) into the cluster: an image registers on a model with 30 inliers
  // or more, and a 3D point is matched from several of the cluster's
  // images.
  int min_matches = 100;
  // A cluster's halo holds at most this share of its own images (the
  // strongest first).
  double max_share = 0.25;

  // Lists the options as --Tmr.* rows (tmr/util/option_table.h).
  void AddTo(OptionTable* table);
  bool Check(std::string* error = nullptr) const;
};

// The halo of every image cluster: images of neighbouring clusters on the
// far side of its strongest verified links, so that the tasks of both
// clusters register them and neighbouring cluster models share cameras and
// points when the tasks end (not in the paper, whose clusters are
// disjoint; the image overlap of COLMAP's hierarchical_mapper). For
// cluster c and each other cluster c', the images j of c' are ranked by
// w_j = sum of n_ij over the images i of c (verified matches, Eq. 1's
// n_ij); the images_per_neighbour best with w_j >= min_matches join c's
// halo, which is then cut to max_share |c| by w_j. `cluster_of` gives each
// image's cluster (-1: none; such images join no halo). Each halo is
// sorted by image index. Deterministic.
std::vector<std::vector<int>> FindClusterHalos(
    const MatchGraph& graph, const std::vector<int>& cluster_of,
    int num_clusters, const ClusterHaloOptions& options);

// Which of a cluster's leaf clusters registers each image of its halo: the
// leaf whose images have the most verified matches with it (the leaf task
// registers it on the kernel's and the leaf's points), the leaf with the
// fewest images and halo images so far when no leaf image matches it.
// Returns one sorted list per leaf; empty lists when there is no leaf.
std::vector<std::vector<int>> AssignHaloToLeaves(
    const MatchGraph& graph, const std::vector<std::vector<int>>& leaves,
    const std::vector<int>& halo);

}  // namespace tmr
