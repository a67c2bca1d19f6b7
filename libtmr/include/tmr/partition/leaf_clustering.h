// Copyright (c) 2026, the tmr authors. BSD-3-Clause.
#pragma once

#include <string>
#include <vector>

#include "tmr/scene/image_graph.h"
#include "tmr/util/option_table.h"

namespace tmr {

struct RadialAgglomerateOptions {
  // Ideal leaf cluster size e = r * m (m: kernel size of the scene).
  double r = 3.0;
  // Weights of Eq. 7: phi = s1*g_d + s2*g_k - s3*g_r + s4*g_c.
  double sigma1 = 1.0;
  double sigma2 = 1.0;
  double sigma3 = 3.0;
  double sigma4 = 1.0;

  // Lists the options as --Tmr.* rows (tmr/util/option_table.h).
  void AddTo(OptionTable* table);
  bool Check(std::string* error = nullptr) const;
};

// Leaf clusters of one image cluster by Radial Agglomerate Clustering (paper
// Sec. 4.3, Eq. 7), K_c = max(1, round(M / (r * m))) for M leaves.
//
// Distances are shortest paths on the image cluster's subgraph of D; the
// distance of a leaf to the kernel is its shortest path to any kernel image,
// and its tree parent is the previous image on that path. Clusters start as
// single leaves and the pair with the smallest phi merges, where
//   g_d = single-link distance (lightest D edge between the two clusters),
//   g_k = distance of the merged cluster to the kernel (its closest leaf),
//   g_r = difference of the two clusters' distances to the kernel,
//   g_c = size of the merged cluster;
// path terms are divided by the largest leaf-to-kernel distance and g_c by
// e, so that the four terms are comparable. A merge is allowed when it keeps
// every leaf's path to the kernel inside its cluster: a cluster whose path
// still leaves it (unanchored) merges only into the cluster holding the next
// image of that path; anchored clusters merge with any adjacent anchored
// cluster. Merging stops at K_c clusters once all are anchored, so there may
// be fewer than K_c. Leaves that cannot reach the kernel inside the cluster
// form one extra leaf cluster. Results are sorted; images are vertex indices.
std::vector<std::vector<int>> RadialAgglomerateClustering(
    const ImageGraph& difference, const std::vector<int>& kernel,
    const std::vector<int>& leaves, int kernel_size,
    const RadialAgglomerateOptions& options);

}  // namespace tmr
