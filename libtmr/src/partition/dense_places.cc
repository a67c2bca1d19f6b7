// Copyright (c) 2026, the tmr authors. BSD-3-Clause.
#include "tmr/partition/dense_places.h"

#include <algorithm>
#include <functional>
#include <numeric>
#include <stdexcept>
#include <tuple>
#include <utility>

#include "scene/union_find.h"

namespace tmr {
namespace {

// The core_neighbors-th largest pair similarity of each image; 0 for an
// image with fewer pairs.
std::vector<double> CoreSimilarities(const ImageGraph& s, int k) {
  std::vector<double> core(s.NumVertices(), 0.0);
  std::vector<double> weights;
  for (int v = 0; v < s.NumVertices(); ++v) {
    const auto [begin, end] = s.Neighbors(v);
    if (end - begin < k) continue;
    weights.clear();
    for (auto* it = begin; it != end; ++it) weights.push_back(it->weight);
    std::nth_element(weights.begin(), weights.begin() + (k - 1), weights.end(),
                     std::greater<double>());
    core[v] = weights[k - 1];
  }
  return core;
}

// A group of at least min_place_size images in the tree of groups. Levels
// are mutual-reachability similarities: a group exists from `birth` (where
// it splits off its parent, read top-down) up to the levels at which its
// images leave it.
struct Group {
  int parent = -1;
  std::vector<int> children;
  int size = 0;
  double birth = 0.0;
  double sum_levels = 0.0;  // sum over its images of the level they leave at
  double Stability() const { return sum_levels - size * birth; }
};

// Builds the tree of groups bottom-up (Kruskal on w, strongest first) and
// records, per image, the group it first belongs to (-1: none) and the level
// at which it leaves that group.
class GroupTree {
 public:
  GroupTree(const ImageGraph& s, const DensePlaceOptions& o)
      : min_size_(o.min_place_size),
        components_(s.NumVertices()),
        component_group_(s.NumVertices(), -1),
        members_(s.NumVertices()),
        first_group_(s.NumVertices(), -1),
        leave_level_(s.NumVertices(), 0.0) {
    for (int v = 0; v < s.NumVertices(); ++v) members_[v] = {v};
    const std::vector<double> core = CoreSimilarities(s, o.core_neighbors);
    std::vector<WeightedEdge> edges = s.Edges();
    for (WeightedEdge& e : edges) {
      e.weight = std::min({e.weight, core[e.u], core[e.v]});
      if (e.u > e.v) std::swap(e.u, e.v);
    }
    std::sort(edges.begin(), edges.end(), [](const auto& a, const auto& b) {
      return std::tie(b.weight, a.u, a.v) < std::tie(a.weight, b.u, b.v);
    });
    for (const WeightedEdge& e : edges) Join(e.u, e.v, e.weight);
  }

  const std::vector<Group>& groups() const { return groups_; }
  int FirstGroup(int v) const { return first_group_[v]; }
  double LeaveLevel(int v) const { return leave_level_[v]; }

 private:
  // Images of a component below min_size that join group g at `level`.
  void Enter(std::vector<int>* images, int g, double level) {
    for (const int v : *images) {
      first_group_[v] = g;
      leave_level_[v] = level;
    }
    groups_[g].size += static_cast<int>(images->size());
    groups_[g].sum_levels += level * static_cast<double>(images->size());
    images->clear();
    images->shrink_to_fit();
  }

  void Join(int u, int v, double level) {
    int a = components_.Find(u), b = components_.Find(v);
    if (a == b) return;
    int ga = component_group_[a], gb = component_group_[b];
    if (ga < 0 && gb >= 0) std::swap(a, b), std::swap(ga, gb);
    // a now holds the group, if either has one.
    components_.Link(b, a);
    if (ga < 0) {  // two small components
      members_[a].insert(members_[a].end(), members_[b].begin(),
                         members_[b].end());
      members_[b].clear();
      if (static_cast<int>(members_[a].size()) >= min_size_) {
        component_group_[a] = NewGroup();
        Enter(&members_[a], component_group_[a], level);
      }
    } else if (gb < 0) {  // a small component falls into the group
      Enter(&members_[b], ga, level);
    } else {  // two groups: both split off the new parent here
      const int parent = NewGroup();
      for (const int g : {ga, gb}) {
        groups_[g].parent = parent;
        groups_[g].birth = level;
        groups_[parent].children.push_back(g);
        groups_[parent].size += groups_[g].size;
      }
      groups_[parent].sum_levels = level * groups_[parent].size;
      component_group_[a] = parent;
    }
    component_group_[b] = -1;
  }

  int NewGroup() {
    groups_.emplace_back();
    return static_cast<int>(groups_.size()) - 1;
  }

  const int min_size_;
  UnionFind components_;
  std::vector<int> component_group_;       // by union-find root
  std::vector<std::vector<int>> members_;  // of components without a group
  std::vector<int> first_group_;
  std::vector<double> leave_level_;
  std::vector<Group> groups_;
};

}  // namespace

bool DensePlaceOptions::Check(std::string* error) const {
  if (min_place_size < 2) {
    if (error) *error = "min_place_size must be >= 2";
    return false;
  }
  if (core_neighbors < 1) {
    if (error) *error = "core_neighbors must be >= 1";
    return false;
  }
  return true;
}

std::vector<DensePlace> FindDensePlaces(const ImageGraph& similarity,
                                        const DensePlaceOptions& options) {
  std::string error;
  if (!options.Check(&error))
    throw std::invalid_argument("DensePlaceOptions: " + error);
  const GroupTree tree(similarity, options);
  const std::vector<Group>& groups = tree.groups();

  // Excess of mass: a group is kept when it is at least as stable as the
  // best selection inside it. Children are made before their parents.
  const int num_groups = static_cast<int>(groups.size());
  std::vector<double> best(num_groups, 0.0);
  std::vector<bool> kept(num_groups, false);
  for (int g = 0; g < num_groups; ++g) {
    double inside = 0.0;
    for (const int c : groups[g].children) inside += best[c];
    kept[g] = groups[g].children.empty() || groups[g].Stability() >= inside;
    best[g] = kept[g] ? groups[g].Stability() : inside;
  }
  // The place of each group: its outermost kept ancestor (or itself).
  std::vector<int> place_of(num_groups, -1);
  for (int g = num_groups - 1; g >= 0; --g) {
    const int parent = groups[g].parent;
    if (parent >= 0 && place_of[parent] >= 0) {
      place_of[g] = place_of[parent];
    } else if (kept[g]) {
      place_of[g] = g;
    }
  }
  // An image belongs to the place of its first group, unless it left that
  // group right where the place begins (it never was inside it).
  std::vector<std::vector<int>> images(num_groups);
  for (int v = 0; v < similarity.NumVertices(); ++v) {
    const int g = tree.FirstGroup(v);
    if (g < 0 || place_of[g] < 0) continue;
    const Group& place = groups[place_of[g]];
    if (tree.LeaveLevel(v) > place.birth) images[place_of[g]].push_back(v);
  }
  std::vector<DensePlace> places;
  for (int g = 0; g < num_groups; ++g) {
    if (place_of[g] != g ||
        static_cast<int>(images[g].size()) < options.min_place_size)
      continue;
    places.push_back(
        {std::move(images[g]), groups[g].birth, groups[g].Stability()});
  }
  std::sort(places.begin(), places.end(),
            [](const DensePlace& a, const DensePlace& b) {
              return a.images < b.images;
            });
  return places;
}

}  // namespace tmr
