// Copyright (c) 2026, the tmr authors. BSD-3-Clause.
#pragma once

#include <string>
#include <vector>

#include "tmr/scene/image_graph.h"

namespace tmr {

struct DensePlaceOptions {
  // A dense place holds at least this many images (HDBSCAN's minimum cluster
  // size); smaller groups are photos of the place they hang off.
  int min_place_size = 30;
  // An image's core similarity is its core_neighbors-th strongest pair
  // (HDBSCAN's min_samples): photos with fewer pairs, on a street or a
  // corridor, are never denser than their sparsest neighbourhood, so a chain
  // of them does not join two places early.
  int core_neighbors = 5;

  bool Check(std::string* error = nullptr) const;
};

struct DensePlace {
  std::vector<int> images;  // sorted vertex indices of S
  // Similarity level at which the place separates from the rest of its
  // connected part (0 for a place that is a whole part).
  double birth = 0.0;
  // HDBSCAN's excess of mass: the sum over its images of how far above
  // `birth` they stay in the place.
  double stability = 0.0;
};

// Dense places of the similarity graph: HDBSCAN* (Campello, Moulavi and
// Sander 2013; the graph form of McInnes and Healy 2017) on S, with the
// mutual-reachability similarity w_ij = min(s_ij, core_i, core_j). The
// maximum spanning forest of w gives, per connected part of S, the tree of
// groups of at least min_place_size images as the level falls; the places
// are the groups of largest total stability with none inside another (the
// excess-of-mass selection, a whole part allowed). Images outside every
// place (streets, corridors, groups below min_place_size) belong to none.
// Deterministic; sorted by smallest image.
std::vector<DensePlace> FindDensePlaces(const ImageGraph& similarity,
                                        const DensePlaceOptions& options);

}  // namespace tmr
