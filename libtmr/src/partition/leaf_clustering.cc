// Copyright (c) 2026, the tmr authors. BSD-3-Clause.
#include "tmr/partition/leaf_clustering.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <queue>
#include <stdexcept>
#include <unordered_map>

namespace tmr {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

struct Cluster {
  std::vector<int> members;  // global vertex indices
  int root = -1;             // member closest to the kernel
  double distance = kInf;    // distance of the root to the kernel
  bool anchored = false;     // the root's path goes straight into the kernel
  bool alive = true;
  int version = 0;
  std::unordered_map<int, double> neighbors;  // cluster -> lightest D edge
};

struct Candidate {
  double phi;
  int a, b, version_a, version_b;
  bool operator>(const Candidate& o) const {
    return std::tie(phi, a, b) > std::tie(o.phi, o.a, o.b);
  }
};

class RadialAgglomeration {
 public:
  RadialAgglomeration(const ImageGraph& d, const std::vector<int>& kernel,
                      const std::vector<int>& leaves, int kernel_size,
                      const RadialAgglomerateOptions& o)
      : d_(d), o_(o), ideal_size_(o.r * kernel_size) {
    const int n = d.NumVertices();
    in_cluster_.assign(n, false);
    is_kernel_.assign(n, false);
    for (const int v : kernel) in_cluster_.at(v) = is_kernel_.at(v) = true;
    for (const int v : leaves) in_cluster_.at(v) = true;
    ShortestPathsToKernel(kernel);
    target_ = std::max<int>(1, std::lround(leaves.size() / ideal_size_));
    double max_distance = 0.0;
    cluster_of_.assign(n, -1);
    for (const int v : leaves) {
      if (distance_[v] == kInf) {
        detached_.push_back(v);
        continue;
      }
      max_distance = std::max(max_distance, distance_[v]);
      cluster_of_[v] = static_cast<int>(clusters_.size());
      Cluster c;
      c.members = {v};
      c.root = v;
      c.distance = distance_[v];
      c.anchored = is_kernel_[parent_[v]];
      clusters_.push_back(std::move(c));
    }
    distance_scale_ = max_distance > 0 ? max_distance : 1.0;
    for (Cluster& c : clusters_) {
      const auto [begin, end] = d.Neighbors(c.root);
      for (auto* it = begin; it != end; ++it) {
        const int other = cluster_of_[it->vertex];
        if (other >= 0) c.neighbors[other] = it->weight;
      }
    }
    num_alive_ = static_cast<int>(clusters_.size());
    for (const Cluster& c : clusters_) num_unanchored_ += !c.anchored;
  }

  std::vector<std::vector<int>> Run() {
    for (int c = 0; c < static_cast<int>(clusters_.size()); ++c) {
      if (clusters_[c].anchored) anchored_.push_back(c);
    }
    for (int c = 0; c < static_cast<int>(clusters_.size()); ++c) {
      if (!clusters_[c].anchored) {
        PushCandidates(c);
        continue;
      }
      // Anchored pairs are pushed once, from their smaller index.
      for (const auto& [other, weight] : clusters_[c].neighbors) {
        if (Allowed(c, other) && !clusters_[other].anchored) Push(c, other);
      }
      for (const int other : anchored_) {
        if (other > c) Push(c, other);
      }
    }
    while (!heap_.empty() && (num_alive_ > target_ || num_unanchored_ > 0)) {
      const Candidate top = heap_.top();
      heap_.pop();
      const Cluster& a = clusters_[top.a];
      const Cluster& b = clusters_[top.b];
      if (!a.alive || !b.alive || a.version != top.version_a ||
          b.version != top.version_b) {
        continue;
      }
      // At the target only merges that anchor a cluster remain.
      if (num_alive_ <= target_ && a.anchored && b.anchored) continue;
      PushCandidates(Merge(top.a, top.b));
    }
    std::vector<std::vector<int>> result;
    for (Cluster& c : clusters_) {
      if (!c.alive) continue;
      std::sort(c.members.begin(), c.members.end());
      result.push_back(std::move(c.members));
    }
    if (!detached_.empty()) {
      std::sort(detached_.begin(), detached_.end());
      result.push_back(detached_);
    }
    std::sort(result.begin(), result.end());
    return result;
  }

 private:
  // Multi-source Dijkstra from the kernel inside the image cluster.
  void ShortestPathsToKernel(const std::vector<int>& kernel) {
    const int n = d_.NumVertices();
    distance_.assign(n, kInf);
    parent_.assign(n, -1);
    using Item = std::pair<double, int>;
    std::priority_queue<Item, std::vector<Item>, std::greater<Item>> queue;
    for (const int v : kernel) {
      distance_[v] = 0.0;
      parent_[v] = v;
      queue.emplace(0.0, v);
    }
    while (!queue.empty()) {
      const auto [dist, v] = queue.top();
      queue.pop();
      if (dist > distance_[v]) continue;
      const auto [begin, end] = d_.Neighbors(v);
      for (auto* it = begin; it != end; ++it) {
        const int u = it->vertex;
        if (!in_cluster_[u] || dist + it->weight >= distance_[u]) continue;
        distance_[u] = dist + it->weight;
        parent_[u] = v;
        queue.emplace(distance_[u], u);
      }
    }
  }

  // Single-link distance: the lightest D edge between the clusters, or the
  // path through the kernel (whose images are all at distance 0).
  double LinkDistance(int a, int b) const {
    const Cluster& x = clusters_[a];
    const Cluster& y = clusters_[b];
    const double through_kernel =
        x.anchored && y.anchored ? x.distance + y.distance : kInf;
    const auto edge = x.neighbors.find(b);
    return edge == x.neighbors.end() ? through_kernel
                                     : std::min(edge->second, through_kernel);
  }

  double Phi(int a, int b) const {
    const Cluster& x = clusters_[a];
    const Cluster& y = clusters_[b];
    const double g_d = LinkDistance(a, b);
    const double g_k = std::min(x.distance, y.distance);
    const double g_r = std::abs(x.distance - y.distance);
    const double g_c = static_cast<double>(x.members.size() + y.members.size());
    return (o_.sigma1 * g_d + o_.sigma2 * g_k - o_.sigma3 * g_r) /
               distance_scale_ +
           o_.sigma4 * g_c / ideal_size_;
  }

  // The cluster an unanchored cluster must merge into: the one holding the
  // next image on its root's path to the kernel.
  int ParentCluster(int c) const {
    return cluster_of_[parent_[clusters_[c].root]];
  }

  bool Allowed(int a, int b) const {
    const Cluster& x = clusters_[a];
    const Cluster& y = clusters_[b];
    if (x.anchored && y.anchored) return true;
    return (!x.anchored && ParentCluster(a) == b) ||
           (!y.anchored && ParentCluster(b) == a);
  }

  void Push(int c, int other) {
    const int a = std::min(c, other), b = std::max(c, other);
    heap_.push({Phi(a, b), a, b, clusters_[a].version, clusters_[b].version});
  }

  // Candidates of cluster c: its allowed neighbours and, when c is
  // anchored, every other anchored cluster (joined through the kernel).
  void PushCandidates(int c) {
    const bool anchored = clusters_[c].anchored;
    for (const auto& [other, weight] : clusters_[c].neighbors) {
      if (Allowed(c, other) && !(anchored && clusters_[other].anchored))
        Push(c, other);
    }
    if (!anchored) return;
    for (const int other : anchored_) {
      if (other != c && clusters_[other].alive && clusters_[other].anchored)
        Push(c, other);
    }
  }

  // Merges the smaller of the two clusters into the larger; returns the
  // surviving cluster.
  int Merge(int a, int b) {
    if (clusters_[a].members.size() < clusters_[b].members.size())
      std::swap(a, b);
    Cluster& keep = clusters_[a];
    Cluster& gone = clusters_[b];
    num_unanchored_ -= !keep.anchored + !gone.anchored;
    const bool gone_is_closer =
        std::tie(gone.distance, gone.root) < std::tie(keep.distance, keep.root);
    if (gone_is_closer) {
      keep.root = gone.root;
      keep.distance = gone.distance;
    }
    const bool was_anchored = keep.anchored;
    keep.anchored = is_kernel_[parent_[keep.root]];
    num_unanchored_ += !keep.anchored;
    if (keep.anchored && !was_anchored) anchored_.push_back(a);
    for (const int v : gone.members) cluster_of_[v] = a;
    keep.members.insert(keep.members.end(), gone.members.begin(),
                        gone.members.end());
    for (const auto& [other, weight] : gone.neighbors) {
      if (other == a) continue;
      const auto found = keep.neighbors.find(other);
      const double lightest = found == keep.neighbors.end()
                                  ? weight
                                  : std::min(found->second, weight);
      keep.neighbors[other] = lightest;
      auto& theirs = clusters_[other].neighbors;
      theirs.erase(b);
      theirs[a] = lightest;
    }
    keep.neighbors.erase(b);
    gone.alive = false;
    gone.members.clear();
    gone.neighbors.clear();
    ++keep.version;
    --num_alive_;
    // Pairs with the merged cluster are re-pushed by the caller; the
    // version bump above invalidates the old ones. Other pairs are intact.
    if (anchored_.size() > 2 * static_cast<size_t>(num_alive_)) {
      anchored_.erase(
          std::remove_if(anchored_.begin(), anchored_.end(),
                         [&](int c) { return !clusters_[c].alive; }),
          anchored_.end());
    }
    return a;
  }

  const ImageGraph& d_;
  const RadialAgglomerateOptions& o_;
  const double ideal_size_;
  int target_ = 1;
  double distance_scale_ = 1.0;
  std::vector<bool> in_cluster_, is_kernel_;
  std::vector<double> distance_;
  std::vector<int> parent_, cluster_of_, detached_;
  std::vector<int> anchored_;  // anchored clusters (may hold dead ones)
  std::vector<Cluster> clusters_;
  int num_alive_ = 0, num_unanchored_ = 0;
  std::priority_queue<Candidate, std::vector<Candidate>,
                      std::greater<Candidate>>
      heap_;
};

}  // namespace

void RadialAgglomerateOptions::AddTo(OptionTable* t) {
  t->Add("Tmr.r", &r, "ideal leaf cluster size e = r * m").Above(0);
  t->Add("Tmr.sigma1", &sigma1, "RAC weight of the cluster distance")
      .AtLeast(0);
  t->Add("Tmr.sigma2", &sigma2, "RAC weight of the distance to the kernel")
      .AtLeast(0);
  t->Add("Tmr.sigma3", &sigma3, "RAC weight of the radial difference")
      .AtLeast(0);
  t->Add("Tmr.sigma4", &sigma4, "RAC weight of the merged size").AtLeast(0);
}

bool RadialAgglomerateOptions::Check(std::string* error) const {
  return CheckOptionRows(*this, error);
}

std::vector<std::vector<int>> RadialAgglomerateClustering(
    const ImageGraph& difference, const std::vector<int>& kernel,
    const std::vector<int>& leaves, int kernel_size,
    const RadialAgglomerateOptions& options) {
  std::string error;
  if (!options.Check(&error))
    throw std::invalid_argument("RadialAgglomerate: " + error);
  if (kernel.empty() || kernel_size < 1) {
    throw std::invalid_argument("RadialAgglomerateClustering: empty kernel");
  }
  if (leaves.empty()) return {};
  return RadialAgglomeration(difference, kernel, leaves, kernel_size, options)
      .Run();
}

}  // namespace tmr
