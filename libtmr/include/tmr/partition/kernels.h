// Copyright (c) 2026, the tmr authors. BSD-3-Clause.
#pragma once

#include <string>
#include <vector>

#include "tmr/partition/dense_places.h"
#include "tmr/scene/image_graph.h"
#include "tmr/util/option_table.h"

namespace tmr {

struct KernelOptions {
  // Kernel size m = min(max_kernel_size, kernel_fraction * Z), Z = images.
  int max_kernel_size = 70;
  double kernel_fraction = 0.15;
  // A kernel has between m and alpha * m images.
  double alpha = 1.5;
  // Number of layers k of the greedy search.
  int num_layers = 15;
  // a = min(s) + epsilon: weaker edges never join a kernel.
  double epsilon = 0.1;
  // Kernels are never smaller than this (a connected part with fewer images
  // gets no kernel and stays unclustered).
  int min_kernel_size = 3;
  // m is at least this, and so is every dense place (per_place) and every
  // kernel but that of a smaller connected part (the whole part). The paper
  // has no floor (3 gives its m); 30 lets every kernel seed a stable model
  // (a 60-image scene's kernels of 9-13 images gave a mirrored model).
  int kernel_size_floor = 30;
  // Search kernels per dense place (FindDensePlaces, places of at least
  // kernel_size_floor images): a place of at most alpha * m images is a
  // kernel, a larger one is searched on the layers of its own similarities.
  // Images outside every place get no kernel and join the nearest kernel's
  // cluster. false: the paper's layered search on the whole graph.
  bool per_place = true;
  // The place search's core neighbours (DensePlaceOptions::core_neighbors).
  int place_core_neighbors = 5;
  // Recursion depth into oversized components before they are carved.
  int max_recursion_depth = 8;

  // Lists the options as --Tmr.* rows (tmr/util/option_table.h).
  void AddTo(OptionTable* table);
  bool Check(std::string* error = nullptr) const;
  // The dense place search of per_place: places of at least the kernel
  // size floor.
  DensePlaceOptions PlaceOptions() const;
  // m for a scene of `num_images` images: at least kernel_size_floor and
  // min_kernel_size.
  int KernelSize(int num_images) const;
};

// How a kernel was found, for reports.
enum class KernelOrigin {
  kPlace,   // a dense place of at most alpha * m images (per_place)
  kLayer,   // a component of size in [m, alpha * m] at some layer (Sec. 4.1)
  kCarved,  // grown from the densest image of an oversized component
  kRescue,  // grown from the densest image of a connected part of S that
            // had no kernel (no dense place)
};

// "place", "layer", "carved" or "rescue" (tree.json, summaries).
const char* KernelOriginName(KernelOrigin origin);

struct Kernel {
  std::vector<int> images;  // sorted vertex indices of S
  KernelOrigin origin = KernelOrigin::kLayer;
  int layer = 0;  // layer (1-based) of the outermost search that found it
};

// Kernels per dense place (per_place, the default): each place of
// FindDensePlaces is a kernel when it holds at most alpha * m images;
// a larger one is searched with the paper's layers (below) on its own
// similarities, and carved if they find nothing.
//
// Multi-layer greedy kernel search (paper Sec. 4.1, Eq. 4):
// theta_i = a + (b - a) / 1.5^(i-1), a = min(s) + epsilon, b = max(s).
// Layer by layer, edges with s > theta_i are added; a connected component
// of size in [m, alpha * m] becomes a kernel and leaves the graph; a larger
// one is searched recursively on [theta_i, max s within it] (the range in
// which it fell apart). A component still too large at the deepest level is
// carved: a kernel of about (1 + alpha) / 2 * m images is grown from its
// densest image along the strongest edges, and the rest is searched again.
// Finally, every connected part of S (all edges) with at least
// min_kernel_size images and no kernel gets one, grown from its densest
// image: the whole part when it is smaller than the kernel.
std::vector<Kernel> FindKernels(const ImageGraph& similarity,
                                const KernelOptions& options);

}  // namespace tmr
