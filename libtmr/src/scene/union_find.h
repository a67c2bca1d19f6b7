// Copyright (c) 2026, the tmr authors. BSD-3-Clause.
// Disjoint sets of vertices 0..n-1 with path halving (private to libtmr).
#pragma once

#include <algorithm>
#include <numeric>
#include <vector>

namespace tmr {

class UnionFind {
 public:
  explicit UnionFind(int n) : parent_(n) {
    std::iota(parent_.begin(), parent_.end(), 0);
  }

  // The root of x's set.
  int Find(int x) {
    while (parent_[x] != x) x = parent_[x] = parent_[parent_[x]];
    return x;
  }

  // Joins the sets of a and b; the smaller root stays the root.
  void Union(int a, int b) {
    a = Find(a), b = Find(b);
    if (a != b) Link(std::max(a, b), std::min(a, b));
  }

  // Puts root `child`'s set under root `root`, for callers that choose the
  // root themselves (both must be roots of different sets).
  void Link(int child, int root) { parent_[child] = root; }

 private:
  std::vector<int> parent_;
};

}  // namespace tmr
