// Copyright (c) 2026, the tmr authors. BSD-3-Clause.
#pragma once

#include <string>
#include <vector>

#include "tmr/scene/image_graph.h"

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
  // m is at least this. The paper has no floor (3 here); tmr_mapper uses 30
  // so that every kernel can seed a stable model even in small scenes.
  int kernel_size_floor = 3;
  // Recursion depth into oversized components before they are carved.
  int max_recursion_depth = 8;

  bool Check(std::string* error = nullptr) const;
  // m for a scene of `num_images` images: at least kernel_size_floor and
  // min_kernel_size.
  int KernelSize(int num_images) const;
};

// How a kernel was found, for reports.
enum class KernelOrigin {
  kLayer,   // a component of size in [m, alpha * m] at some layer (Sec. 4.1)
  kCarved,  // grown from the densest image of an oversized component
  kRescue,  // the best part of a connected part of S that had no kernel
};

struct Kernel {
  std::vector<int> images;  // sorted vertex indices of S
  KernelOrigin origin = KernelOrigin::kLayer;
  int layer = 0;  // layer (1-based) of the outermost search that found it
};

// Multi-layer greedy kernel search (paper Sec. 4.1, Eq. 4):
// theta_i = a + (b - a) / 1.5^(i-1), a = min(s) + epsilon, b = max(s).
// Layer by layer, edges with s > theta_i are added; a connected component
// of size in [m, alpha * m] becomes a kernel and leaves the graph; a larger
// one is searched recursively on [theta_i, max s within it] (the range in
// which it fell apart). A component still too large at the deepest level is
// carved: a kernel of about (1 + alpha) / 2 * m images is grown from its
// densest image along the strongest edges, and the rest is searched again.
// Finally, every connected part of S (all edges) with at least
// min_kernel_size images and no kernel gets one: its largest component at
// the last layer, or a kernel grown from its densest image.
std::vector<Kernel> FindKernels(const ImageGraph& similarity,
                                const KernelOptions& options);

}  // namespace tmr
