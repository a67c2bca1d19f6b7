// Copyright (c) 2026, the tmr authors. BSD-3-Clause.
// The force-directed layout of the partition picture.
#pragma once

#include <array>
#include <vector>

#include "tmr/scene/image_graph.h"

namespace tmr {

struct ForceLayoutOptions {
  // Linear cooling to 0 over these; 1,000 unfold a city of 3,752 images
  // (36 blocks) into its streets, 400 leave some folded.
  int iterations = 1000;
  // Largest move of a vertex in the first iteration, in units of k, the
  // ideal edge length (k = 1).
  double initial_temperature = 2.0;
  // Barnes-Hut opening angle: a cell of side s at distance d acts as one
  // body when s / d < theta (0: every pair, exact).
  double theta = 0.8;
  unsigned seed = 7;  // of the random start

  bool Check() const {
    return iterations >= 0 && initial_temperature >= 0 && theta >= 0;
  }
};

// Fruchterman and Reingold's force-directed layout (attraction d^2 / k along
// the edges, repulsion k^2 / d between every pair of vertices), with the
// repulsion summed over a quadtree as Barnes and Hut do: O(n log n) per
// iteration instead of O(n^2). Boost.Graph's layout is O(n^2) here: its
// grid_force_pairs sizes its cells 2 * area / sqrt(n) instead of
// 2 * sqrt(area / n), so one cell holds every vertex (82 s for 3,752
// images), and a correct grid, repulsion within 2k only, leaves a large
// city's streets folded onto each other. Each connected component is laid
// out on its own and the components are packed in rows, largest first.
// Returns a position per vertex; the same graph and options give the same
// layout.
std::vector<std::array<double, 2>> ForceDirectedLayout(
    const ImageGraph& graph, const ForceLayoutOptions& options = {});

// The layout moved and scaled into [0, 1] x [0, 1], its longer side
// spanning it (the aspect kept), for drawing.
std::vector<std::array<double, 2>> LayoutInUnitSquare(
    const std::vector<std::array<double, 2>>& layout);

}  // namespace tmr
