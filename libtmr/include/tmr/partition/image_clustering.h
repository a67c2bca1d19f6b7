// Copyright (c) 2026, the tmr authors. BSD-3-Clause.
#pragma once

#include <string>
#include <vector>

#include "tmr/scene/image_graph.h"
#include "tmr/util/option_table.h"

namespace tmr {

struct MultiLayerShortestPathOptions {
  // Number of layers L: [min d, max d] is cut into L equal steps (Eq. 6).
  int num_layers = 20;
  // A pair that is the only link between two groups of at least this many
  // images (a bridge of D: one photo to one photo) is never on a path, so
  // it cannot pull a group into the cluster of a kernel on its other side;
  // such a group without a kernel stays unclustered. A pair inside a kernel
  // is kept. 0 keeps every pair (the paper).
  int min_bridge_side = 2;

  // Lists the options as --Tmr.* rows (tmr/util/option_table.h).
  void AddTo(OptionTable* table);
  bool Check(std::string* error = nullptr) const;
};

struct ImageClusters {
  // Cluster (kernel index) of every image, -1 when it reaches no exemplar.
  std::vector<int> cluster;
  // Layer (1-based) in which the image was assigned; 0 for kernel images and
  // unclustered ones.
  std::vector<int> layer;
  // Length of its optimal reconstruction path to the exemplar (sum of d).
  std::vector<double> path_length;
};

// Image clustering by Multi-layer Shortest Path (paper Sec. 4.2, Eq. 6) on
// the difference graph D. Layer t keeps the edges with d < phi_t =
// min d + t * (max d - min d) / L (the last layer keeps all edges). In each
// layer one multi-source Dijkstra (Boost.Graph) from all exemplars reaches
// every still unassigned image by its shortest path; the image joins the
// cluster of the first clustered image on that path back to the exemplar
// (usually the exemplar's own; another cluster's when the path passes
// through its images), so every cluster is connected through its own images.
// It keeps that cluster in later layers. Kernel images belong to their
// kernel from the start. Paths found in an early layer avoid weak overlaps
// (large d), as the paper's Fig. 5 asks. Not in the paper: paths never
// cross a single-pair link between two groups (min_bridge_side).
ImageClusters AssignByMultiLayerShortestPath(
    const ImageGraph& difference, const std::vector<std::vector<int>>& kernels,
    const std::vector<int>& exemplars,
    const MultiLayerShortestPathOptions& options);

}  // namespace tmr
