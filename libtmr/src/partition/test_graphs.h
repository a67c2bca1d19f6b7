// Copyright (c) 2026, the tmr authors. BSD-3-Clause.
// Hand-made similarity graphs with known answers for the partition tests.
#pragma once

#include <algorithm>
#include <string>
#include <tuple>
#include <vector>

#include "tmr/partition/kernels.h"
#include "tmr/scene/image_graph.h"
#include "tmr/scene/match_graph.h"

namespace tmr {
namespace test {

// Builds a match graph whose similarity graph has exactly the given
// weights: n_i = 1000 for every image and n_ij chosen so that
// s_ij = n_ij / (2000 - n_ij) equals the weight.
inline MatchGraph MatchGraphWithSimilarities(
    int num_images, const std::vector<WeightedEdge>& edges) {
  MatchGraph graph;
  for (int i = 0; i < num_images; ++i) {
    graph.images.push_back({static_cast<uint32_t>(i + 1),
                            "img" + std::to_string(i), 1, 2000, 1000});
  }
  for (const WeightedEdge& e : edges) {
    // s = n / (2000 - n)  <=>  n = 2000 s / (1 + s); the similarity graph
    // then holds the rounded value, close to the weight.
    const int n = static_cast<int>(2000.0 * e.weight / (1.0 + e.weight) + 0.5);
    graph.pairs.push_back({std::min(e.u, e.v), std::max(e.u, e.v), n, 2});
  }
  std::sort(
      graph.pairs.begin(), graph.pairs.end(), [](const auto& a, const auto& b) {
        return std::tie(a.image1, a.image2) < std::tie(b.image1, b.image2);
      });
  return graph;
}

// The paper's kernel search at the scale of these hand-made graphs of tens
// of images: its floor of 3 instead of 30, the layers on the whole graph
// instead of per dense place.
inline KernelOptions PaperKernelOptions() {
  KernelOptions options;
  options.kernel_size_floor = 3;
  options.per_place = false;
  return options;
}

// Dense places of the given sizes, each a ring of cameras that sees its
// neighbours up to 12 positions away (s = 0.3 next to each other, falling
// to 0.05), chained in order by streets of `street_length` images (each
// sees the next two, s = 0.04 and 0.02; its ends see two place images at
// s = 0.02; no street and no link for street_length 0). Images: the places
// first, in order, then the streets.
struct PlacesAndStreets {
  std::vector<std::vector<int>> places;
  std::vector<int> streets;
  std::vector<WeightedEdge> edges;
  int num_images = 0;

  PlacesAndStreets(const std::vector<int>& sizes, int street_length) {
    for (const int n : sizes) {
      places.emplace_back();
      for (int i = 0; i < n; ++i) places.back().push_back(num_images + i);
      for (int i = 0; i < n; ++i) {
        for (int d = 1; d <= std::min(12, n / 2); ++d) {
          const int j = (i + d) % n;
          if (2 * d == n && j < i) continue;  // the opposite pair once
          edges.push_back(
              {num_images + i, num_images + j, 0.05 + 0.25 * (12 - d) / 11.0});
        }
      }
      num_images += n;
    }
    for (size_t p = 0; street_length > 0 && p + 1 < places.size(); ++p) {
      std::vector<int> street;
      for (int i = 0; i < street_length; ++i) street.push_back(num_images++);
      for (int i = 0; i < street_length; ++i) {
        if (i + 1 < street_length)
          edges.push_back({street[i], street[i + 1], 0.04});
        if (i + 2 < street_length)
          edges.push_back({street[i], street[i + 2], 0.02});
      }
      for (const int k : {0, 1}) {
        edges.push_back({places[p][k], street.front(), 0.02});
        edges.push_back({places[p + 1][k], street.back(), 0.02});
      }
      streets.insert(streets.end(), street.begin(), street.end());
    }
  }
};

// Two dense groups of `group` images (s = 0.5 inside), each with `leaves`
// leaf images hanging off it (s = 0.15 to two group images, 0.12 to the
// previous leaf), optionally joined by a thin chain of 4 images (s = 0.03).
// Images: group A = [0, group), its leaves next, then group B and its
// leaves, then the chain.
struct TwoGroups {
  int group_size, num_leaves;
  bool chain;
  std::vector<WeightedEdge> edges;
  int num_images = 0;
  std::vector<int> group_a, group_b, leaves_a, leaves_b, chain_images;

  TwoGroups(int group, int leaves, bool with_chain)
      : group_size(group), num_leaves(leaves), chain(with_chain) {
    AddGroup(&group_a, &leaves_a);
    AddGroup(&group_b, &leaves_b);
    if (chain) {
      int previous = group_a[0];
      for (int k = 0; k < 4; ++k) {
        chain_images.push_back(num_images);
        edges.push_back({previous, num_images, 0.03});
        previous = num_images++;
      }
      edges.push_back({previous, group_b[0], 0.03});
    }
  }

 private:
  void AddGroup(std::vector<int>* group, std::vector<int>* leaves) {
    for (int i = 0; i < group_size; ++i) group->push_back(num_images++);
    for (int i = 0; i < group_size; ++i) {
      for (int j = i + 1; j < group_size; ++j)
        edges.push_back({(*group)[i], (*group)[j], 0.5});
    }
    for (int l = 0; l < num_leaves; ++l) {
      const int v = num_images++;
      edges.push_back({(*group)[l % group_size], v, 0.15});
      edges.push_back({(*group)[(l + 1) % group_size], v, 0.15});
      if (l > 0) edges.push_back({leaves->back(), v, 0.12});
      leaves->push_back(v);
    }
  }
};

}  // namespace test
}  // namespace tmr
