// Copyright (c) 2026, the tmr authors. BSD-3-Clause.
#include "tmr/partition/kernels.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <numeric>
#include <stdexcept>
#include <utility>

#include "scene/union_find.h"
#include "tmr/partition/dense_places.h"

namespace tmr {
namespace {

class KernelSearch {
 public:
  KernelSearch(const ImageGraph& s, const KernelOptions& o)
      : s_(s),
        o_(o),
        m_(o.KernelSize(s.NumVertices())),
        max_size_(std::max(m_, static_cast<int>(std::floor(o.alpha * m_)))),
        active_(s.NumVertices(), true),
        in_set_(s.NumVertices(), false),
        local_(s.NumVertices(), -1),
        link_(s.NumVertices(), 0.0) {}

  // Searches the active vertices of `vertices` on the layers of [a, b].
  // Returns the number of kernels found.
  int Search(const std::vector<int>& vertices, double a, double b, int depth,
             int outer_layer) {
    int found = 0;
    for (int i = 1; i <= o_.num_layers; ++i) {
      const double theta = a + (b - a) / std::pow(1.5, i - 1);
      const int layer = depth == 0 ? i : outer_layer;
      for (const std::vector<int>& component : Components(vertices, theta)) {
        const int size = static_cast<int>(component.size());
        if (size >= m_ && size <= max_size_) {
          AddKernel(component, KernelOrigin::kLayer, layer);
          ++found;
        } else if (size > max_size_) {
          // Recursing is pointless when the component is the whole input
          // again: its weights cannot split it on this range.
          const bool splits = depth == 0 || size < CountActive(vertices);
          const double b_c = MaxWeightWithin(component);
          int inner = 0;
          if (splits && depth < o_.max_recursion_depth && b_c > theta) {
            inner = Search(component, theta, b_c, depth + 1, layer);
          }
          if (inner == 0) {
            Carve(component, theta, KernelOrigin::kCarved, layer);
            inner = 1;
          }
          found += inner;
        }
      }
    }
    return found;
  }

  // The kernels of a dense place: the place itself when it is small enough,
  // else the layered search on the range of its own similarities, else a
  // kernel carved from its densest image.
  void SearchPlace(const std::vector<int>& place) {
    if (static_cast<int>(place.size()) <= max_size_) {
      AddKernel(place, KernelOrigin::kPlace, 0);
      return;
    }
    const auto [min_s, max_s] = WeightRangeWithin(place);
    const double a = std::min(min_s + o_.epsilon, max_s);
    if (Search(place, a, max_s, 0, 0) == 0)
      Carve(place, -1.0, KernelOrigin::kCarved, 0);
  }

  // Gives a kernel to every connected part of S without one. A part below
  // the floor becomes one kernel whole: it has no other kernel to join.
  void Rescue() {
    std::vector<int> all(s_.NumVertices());
    std::iota(all.begin(), all.end(), 0);
    std::vector<bool> has_kernel(s_.NumVertices(), false);
    for (const Kernel& k : kernels_) {
      for (const int v : k.images) has_kernel[v] = true;
    }
    // Components of S with all edges; parts without a kernel are all free.
    std::fill(active_.begin(), active_.end(), true);
    for (const std::vector<int>& part : Components(all, -1.0)) {
      if (static_cast<int>(part.size()) < o_.min_kernel_size) continue;
      if (std::any_of(part.begin(), part.end(),
                      [&](int v) { return has_kernel[v]; })) {
        continue;
      }
      Carve(part, -1.0, KernelOrigin::kRescue, o_.num_layers);
    }
  }

  // Kernels sorted by their smallest image.
  std::vector<Kernel> Take() {
    std::sort(
        kernels_.begin(), kernels_.end(),
        [](const Kernel& x, const Kernel& y) { return x.images < y.images; });
    return std::move(kernels_);
  }

 private:
  // Components (size >= 2) of the active vertices of `vertices` joined by
  // edges with weight > theta, each sorted, ordered by smallest vertex.
  // O(size of `vertices` and their edges): a search per dense place costs
  // what the place holds, not what the scene does.
  std::vector<std::vector<int>> Components(const std::vector<int>& vertices,
                                           double theta) {
    std::vector<int> members;  // the active vertices; local_ indexes them
    for (const int v : vertices) {
      if (!active_[v]) continue;
      local_[v] = static_cast<int>(members.size());
      members.push_back(v);
    }
    UnionFind uf(static_cast<int>(members.size()));
    for (int i = 0; i < static_cast<int>(members.size()); ++i) {
      const auto [begin, end] = s_.Neighbors(members[i]);
      for (auto* it = begin; it != end; ++it) {
        const int j = local_[it->vertex];
        if (j > i && it->weight > theta) uf.Union(i, j);
      }
    }
    std::map<int, std::vector<int>> groups;
    for (int i = 0; i < static_cast<int>(members.size()); ++i)
      groups[uf.Find(i)].push_back(members[i]);
    for (const int v : members) local_[v] = -1;
    std::vector<std::vector<int>> result;
    for (auto& [root, group] : groups) {
      if (group.size() < 2) continue;
      std::sort(group.begin(), group.end());
      result.push_back(std::move(group));
    }
    std::sort(result.begin(), result.end());
    return result;
  }

  // in_set_: the active vertices of `vertices` (Unmark clears them again, so
  // that in_set_ stays all false between calls).
  void Mark(const std::vector<int>& vertices) {
    for (const int v : vertices) in_set_[v] = active_[v];
  }
  void Unmark(const std::vector<int>& vertices) {
    for (const int v : vertices) in_set_[v] = false;
  }

  int CountActive(const std::vector<int>& vertices) const {
    return static_cast<int>(std::count_if(vertices.begin(), vertices.end(),
                                          [&](int v) { return active_[v]; }));
  }

  double MaxWeightWithin(const std::vector<int>& component) {
    return WeightRangeWithin(component).second;
  }

  // Smallest and largest weight of the edges between active vertices of
  // `component` (+inf and -inf without such an edge).
  std::pair<double, double> WeightRangeWithin(
      const std::vector<int>& component) {
    Mark(component);
    double low = std::numeric_limits<double>::infinity();
    double high = -low;
    for (const int v : component) {
      const auto [begin, end] = s_.Neighbors(v);
      for (auto* it = begin; it != end; ++it) {
        if (!in_set_[it->vertex]) continue;
        low = std::min(low, it->weight);
        high = std::max(high, it->weight);
      }
    }
    Unmark(component);
    return {low, high};
  }

  // Grows a kernel of about (1 + alpha) / 2 * m images from the active image
  // of `component` with the largest summed similarity over edges > theta,
  // adding each time the image with the largest summed similarity to it.
  void Carve(const std::vector<int>& component, double theta,
             KernelOrigin origin, int layer) {
    Mark(component);
    auto strength = [&](int v) {
      double sum = 0.0;
      const auto [begin, end] = s_.Neighbors(v);
      for (auto* it = begin; it != end; ++it) {
        if (in_set_[it->vertex] && it->weight > theta) sum += it->weight;
      }
      return sum;
    };
    int seed = -1;
    double best = -1.0;
    for (const int v : component) {
      if (!in_set_[v]) continue;
      const double value = strength(v);
      if (value > best) best = value, seed = v;
    }
    const int target = std::min<int>(std::lround((1.0 + o_.alpha) / 2.0 * m_),
                                     CountActive(component));
    std::vector<int> kernel;
    for (int v = seed; v >= 0 && static_cast<int>(kernel.size()) < target;) {
      kernel.push_back(v);
      in_set_[v] = false;
      const auto [begin, end] = s_.Neighbors(v);
      for (auto* it = begin; it != end; ++it) {
        if (in_set_[it->vertex] && it->weight > theta)
          link_[it->vertex] += it->weight;
      }
      v = -1;
      double strongest = 0.0;
      for (const int u : component) {
        if (in_set_[u] && link_[u] > strongest) strongest = link_[u], v = u;
      }
    }
    Unmark(component);
    for (const int v : component) link_[v] = 0.0;
    if (static_cast<int>(kernel.size()) < o_.min_kernel_size) return;
    std::sort(kernel.begin(), kernel.end());
    AddKernel(kernel, origin, layer);
  }

  void AddKernel(const std::vector<int>& images, KernelOrigin origin,
                 int layer) {
    for (const int v : images) active_[v] = false;
    kernels_.push_back({images, origin, layer});
  }

  const ImageGraph& s_;
  const KernelOptions& o_;
  const int m_;
  const int max_size_;
  std::vector<bool> active_;
  std::vector<bool> in_set_;  // all false outside Mark ... Unmark
  std::vector<int> local_;    // -1 outside Components
  std::vector<double> link_;  // 0 outside Carve
  std::vector<Kernel> kernels_;
};

}  // namespace

const char* KernelOriginName(KernelOrigin origin) {
  switch (origin) {
    case KernelOrigin::kPlace:
      return "place";
    case KernelOrigin::kLayer:
      return "layer";
    case KernelOrigin::kCarved:
      return "carved";
    case KernelOrigin::kRescue:
      return "rescue";
  }
  return "layer";
}

void KernelOptions::AddTo(OptionTable* t) {
  t->Add("Tmr.max_kernel_size", &max_kernel_size,
         "m = min(this, kernel_fraction * images)")
      .AtLeast(2);
  t->Add("Tmr.kernel_fraction", &kernel_fraction,
         "kernel size as a share of the images")
      .Above(0)
      .AtMost(1);
  t->Add("Tmr.alpha", &alpha, "kernels hold m to alpha * m images").AtLeast(1);
  t->Add("Tmr.kernel_layers", &num_layers, "layers k of the kernel search")
      .AtLeast(1);
  t->Add("Tmr.epsilon", &epsilon, "a = min(s) + epsilon").AtLeast(0);
  t->Add("Tmr.min_kernel_size", &min_kernel_size, "smallest kernel").AtLeast(2);
  t->Add("Tmr.kernel_size_floor", &kernel_size_floor,
         "m, and every dense place, is at least this (the paper: 3)")
      .AtLeast(2);
  t->Add("Tmr.kernels_per_place", &per_place,
         "search kernels per dense place (0: the paper's layers on the whole "
         "graph)");
  t->Add("Tmr.place_core_neighbors", &place_core_neighbors,
         "an image's density is its this-th strongest pair (dense places)")
      .AtLeast(1);
  t->Add("Tmr.max_recursion_depth", &max_recursion_depth,
         "recursion into oversized components before they are carved")
      .AtLeast(0);
}

bool KernelOptions::Check(std::string* error) const {
  if (!CheckOptionRows(*this, error)) return false;
  for (const int size : {min_kernel_size, kernel_size_floor}) {
    if (size > max_kernel_size) {
      if (error) {
        *error =
            "Tmr.min_kernel_size and Tmr.kernel_size_floor must be at "
            "most Tmr.max_kernel_size";
      }
      return false;
    }
  }
  return true;
}

DensePlaceOptions KernelOptions::PlaceOptions() const {
  DensePlaceOptions places;
  places.min_place_size = std::max(min_kernel_size, kernel_size_floor);
  places.core_neighbors = place_core_neighbors;
  return places;
}

int KernelOptions::KernelSize(int num_images) const {
  const int m = static_cast<int>(std::lround(
      std::min<double>(max_kernel_size, kernel_fraction * num_images)));
  return std::max({m, min_kernel_size, kernel_size_floor});
}

std::vector<Kernel> FindKernels(const ImageGraph& similarity,
                                const KernelOptions& options) {
  std::string error;
  if (!options.Check(&error))
    throw std::invalid_argument("KernelOptions: " + error);
  KernelSearch search(similarity, options);
  if (similarity.NumEdges() > 0 && options.per_place) {
    for (const DensePlace& place :
         FindDensePlaces(similarity, options.PlaceOptions()))
      search.SearchPlace(place.images);
  } else if (similarity.NumEdges() > 0) {
    const double b = similarity.MaxWeight();
    const double a = std::min(similarity.MinWeight() + options.epsilon, b);
    std::vector<int> all(similarity.NumVertices());
    std::iota(all.begin(), all.end(), 0);
    search.Search(all, a, b, 0, 0);
  }
  search.Rescue();
  return search.Take();
}

}  // namespace tmr
