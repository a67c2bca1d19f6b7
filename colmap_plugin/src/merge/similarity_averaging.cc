// Copyright (c) 2026, the tmr authors. BSD-3-Clause.
#include "merge/similarity_averaging.h"

#include <ceres/ceres.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <numeric>
#include <queue>
#include <sstream>
#include <stdexcept>

namespace tmr {
namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();

// How far two placements of model2 in model1's frame put the link's points
// apart: the median distance, over the link's viewing distance in model1's
// units (through `link_from`, the link's own similarity).
double RelativeDisagreement(const SimilarityLink& link,
                            const colmap::Sim3d& link_from,
                            const colmap::Sim3d& other) {
  std::vector<double> distances;
  distances.reserve(link.points2.size());
  for (const Eigen::Vector3d& p : link.points2)
    distances.push_back((link_from * p - other * p).norm());
  auto middle = distances.begin() + distances.size() / 2;
  std::nth_element(distances.begin(), middle, distances.end());
  return *middle / (link.scale2 * link_from.scale());
}

std::string Percent(double share) {
  std::ostringstream text;
  text.precision(2);
  text << std::fixed << 100 * share << "%";
  return text.str();
}

// The accepted links as a graph: model a's similarity from model b.
class LinkGraph {
 public:
  LinkGraph(int num_models, const std::vector<SimilarityLink>& links,
            const std::vector<bool>& accepted)
      : neighbours_(num_models) {
    for (int l = 0; l < static_cast<int>(links.size()); ++l) {
      if (!accepted[l]) continue;
      const SimilarityLink& link = links[l];
      neighbours_[link.model1].push_back(link.model2);
      neighbours_[link.model2].push_back(link.model1);
      from_[{link.model1, link.model2}] = link.model1_from_model2;
      from_[{link.model2, link.model1}] =
          colmap::Inverse(link.model1_from_model2);
    }
    for (std::vector<int>& n : neighbours_) std::sort(n.begin(), n.end());
  }
  const std::vector<int>& Neighbours(int model) const {
    return neighbours_[model];
  }
  const colmap::Sim3d& From(int a, int b) const { return from_.at({a, b}); }

 private:
  std::vector<std::vector<int>> neighbours_;
  std::map<std::pair<int, int>, colmap::Sim3d> from_;
};

// Refuses, the worst first, links that more triangles of links through
// them contradict than confirm.
void RefuseLinksBrokenByLoops(const std::vector<SimilarityLink>& links,
                              int num_models, double max_loop_error,
                              std::vector<bool>* accepted,
                              std::vector<std::string>* reason) {
  while (true) {
    const LinkGraph graph(num_models, links, *accepted);
    int worst = -1, worst_score = 0, worst_loops = 0;
    for (int l = 0; l < static_cast<int>(links.size()); ++l) {
      if (!(*accepted)[l]) continue;
      const SimilarityLink& link = links[l];
      std::vector<int> common;
      std::set_intersection(graph.Neighbours(link.model1).begin(),
                            graph.Neighbours(link.model1).end(),
                            graph.Neighbours(link.model2).begin(),
                            graph.Neighbours(link.model2).end(),
                            std::back_inserter(common));
      int score = 0;
      for (const int c : common) {
        const colmap::Sim3d via =
            graph.From(link.model1, c) * graph.From(c, link.model2);
        score += RelativeDisagreement(link, link.model1_from_model2, via) >
                         max_loop_error
                     ? 1
                     : -1;
      }
      if (score <= 0) continue;
      if (worst < 0 || score > worst_score ||
          (score == worst_score && link.weight < links[worst].weight)) {
        worst = l;
        worst_score = score;
        worst_loops = static_cast<int>(common.size());
      }
    }
    if (worst < 0) return;
    (*accepted)[worst] = false;
    const int broken = (worst_loops + worst_score) / 2;
    (*reason)[worst] = "it breaks " + std::to_string(broken) + " of the " +
                       std::to_string(worst_loops) +
                       " loops of three models through it (by more than " +
                       Percent(max_loop_error) + " of the viewing distance)";
  }
}

// Each model's part (its lowest-index model) and its pose there along a
// spanning tree of the strongest accepted links.
void PlaceAlongSpanningTree(const std::vector<SimilarityLink>& links,
                            const std::vector<bool>& accepted,
                            SimilarityAveraging* result) {
  const int n = static_cast<int>(result->part.size());
  std::vector<int> order;
  for (int l = 0; l < static_cast<int>(links.size()); ++l)
    if (accepted[l]) order.push_back(l);
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) {
    return links[a].weight > links[b].weight;
  });
  std::vector<int> root(n);
  std::iota(root.begin(), root.end(), 0);
  const auto find = [&](int x) {
    while (root[x] != x) x = root[x] = root[root[x]];
    return x;
  };
  std::vector<bool> tree(links.size(), false);
  for (const int l : order) {
    const int a = find(links[l].model1), b = find(links[l].model2);
    if (a == b) continue;
    root[std::max(a, b)] = std::min(a, b);
    tree[l] = true;
  }
  const LinkGraph graph(n, links, tree);
  std::vector<bool> placed(n, false);
  for (int start = 0; start < n; ++start) {
    if (placed[start]) continue;
    // Lowest index first: the part's first model is its frame.
    std::queue<int> next;
    next.push(start);
    placed[start] = true;
    result->part[start] = start;
    result->part_from_model[start] = colmap::Sim3d();
    while (!next.empty()) {
      const int a = next.front();
      next.pop();
      for (const int b : graph.Neighbours(a)) {
        if (placed[b]) continue;
        placed[b] = true;
        result->part[b] = start;
        result->part_from_model[b] =
            result->part_from_model[a] * graph.From(a, b);
        next.push(b);
      }
    }
  }
}

// A point of a link, moved by both models' placements, should land at one
// place; the residual is their distance over the link's viewing distance
// in the part's frame.
struct LinkPointCost {
  LinkPointCost(const Eigen::Vector3d& in_model1,
                const Eigen::Vector3d& in_model2, double inverse_length)
      : in_model1_(in_model1),
        in_model2_(in_model2),
        inverse_length_(inverse_length) {}

  template <typename T>
  bool operator()(const T* q1, const T* t1, const T* log_s1, const T* q2,
                  const T* t2, const T* log_s2, T* residuals) const {
    const Eigen::Map<const Eigen::Quaternion<T>> r1(q1), r2(q2);
    const Eigen::Map<const Eigen::Matrix<T, 3, 1>> s1(t1), s2(t2);
    const Eigen::Matrix<T, 3, 1> x1 =
        ceres::exp(log_s1[0]) * (r1 * in_model1_.cast<T>()) + s1;
    const Eigen::Matrix<T, 3, 1> x2 =
        ceres::exp(log_s2[0]) * (r2 * in_model2_.cast<T>()) + s2;
    for (int i = 0; i < 3; ++i)
      residuals[i] = (x1[i] - x2[i]) * T(inverse_length_);
    return true;
  }

 private:
  Eigen::Vector3d in_model1_;
  Eigen::Vector3d in_model2_;
  double inverse_length_;
};

// Robust least squares over the accepted links, from the placement in
// `result` (each part's first model held).
void AverageOverLinks(const std::vector<SimilarityLink>& links,
                      const std::vector<bool>& accepted,
                      const SimilarityAveragingOptions& options,
                      SimilarityAveraging* result) {
  const int n = static_cast<int>(result->part.size());
  struct Pose {
    Eigen::Vector4d q;
    Eigen::Vector3d t;
    double log_s;
  };
  std::vector<Pose> poses(n);
  for (int m = 0; m < n; ++m) {
    const colmap::Sim3d& s = result->part_from_model[m];
    poses[m] = {s.rotation().coeffs(), s.translation(), std::log(s.scale())};
  }
  ceres::Problem problem;
  int num_residuals = 0;
  for (int l = 0; l < static_cast<int>(links.size()); ++l) {
    if (!accepted[l]) continue;
    const SimilarityLink& link = links[l];
    const int step = std::max<int>(
        1, static_cast<int>(link.points2.size()) / options.max_points_per_link);
    const double length =
        link.scale2 * result->part_from_model[link.model2].scale();
    Pose& a = poses[link.model1];
    Pose& b = poses[link.model2];
    for (size_t i = 0; i < link.points2.size(); i += step) {
      const Eigen::Vector3d& p = link.points2[i];
      problem.AddResidualBlock(
          new ceres::AutoDiffCostFunction<LinkPointCost, 3, 4, 3, 1, 4, 3, 1>(
              new LinkPointCost(link.model1_from_model2 * p, p, 1 / length)),
          new ceres::CauchyLoss(options.max_relative_error), a.q.data(),
          a.t.data(), &a.log_s, b.q.data(), b.t.data(), &b.log_s);
      ++num_residuals;
    }
  }
  if (num_residuals == 0) return;
  for (int m = 0; m < n; ++m) {
    Pose& pose = poses[m];
    if (!problem.HasParameterBlock(pose.q.data())) continue;
    problem.SetManifold(pose.q.data(), new ceres::EigenQuaternionManifold);
    if (result->part[m] == m) {
      problem.SetParameterBlockConstant(pose.q.data());
      problem.SetParameterBlockConstant(pose.t.data());
      problem.SetParameterBlockConstant(&pose.log_s);
    }
  }
  ceres::Solver::Options solver;
  solver.linear_solver_type = ceres::SPARSE_NORMAL_CHOLESKY;
  solver.max_num_iterations = 100;
  solver.num_threads = 1;
  ceres::Solver::Summary summary;
  ceres::Solve(solver, &problem, &summary);
  for (int m = 0; m < n; ++m) {
    const Pose& pose = poses[m];
    result->part_from_model[m] = colmap::Sim3d(
        std::exp(pose.log_s), Eigen::Quaterniond(pose.q).normalized(), pose.t);
  }
}

// Each link's disagreement with the placement.
void MeasureLinks(const std::vector<SimilarityLink>& links,
                  SimilarityAveraging* result) {
  for (size_t l = 0; l < links.size(); ++l) {
    const SimilarityLink& link = links[l];
    result->relative_error[l] =
        result->part[link.model1] != result->part[link.model2]
            ? kInfinity
            : RelativeDisagreement(
                  link, link.model1_from_model2,
                  colmap::Inverse(result->part_from_model[link.model1]) *
                      result->part_from_model[link.model2]);
  }
}

}  // namespace

void SimilarityAveragingOptions::Check() const {
  if (!(max_relative_error > 0) || !(max_loop_error > 0) || max_rounds < 1 ||
      max_points_per_link < 1)
    throw std::invalid_argument("SimilarityAveragingOptions: out of range");
}

SimilarityAveraging AverageSimilarities(
    int num_models, const std::vector<SimilarityLink>& links,
    const SimilarityAveragingOptions& options) {
  options.Check();
  for (const SimilarityLink& link : links) {
    if (link.model1 < 0 || link.model2 < 0 || link.model1 >= num_models ||
        link.model2 >= num_models || link.model1 == link.model2 ||
        link.points2.empty() || !(link.scale2 > 0))
      throw std::invalid_argument("AverageSimilarities: a malformed link");
  }
  SimilarityAveraging result;
  result.part.resize(num_models);
  result.part_from_model.resize(num_models);
  result.accepted.assign(links.size(), true);
  result.relative_error.assign(links.size(), 0.0);
  result.reason.assign(links.size(), "");
  RefuseLinksBrokenByLoops(links, num_models, options.max_loop_error,
                           &result.accepted, &result.reason);
  for (int round = 0; round < options.max_rounds; ++round) {
    PlaceAlongSpanningTree(links, result.accepted, &result);
    AverageOverLinks(links, result.accepted, options, &result);
    MeasureLinks(links, &result);
    int worst = -1;
    for (int l = 0; l < static_cast<int>(links.size()); ++l) {
      if (result.accepted[l] &&
          result.relative_error[l] > options.max_relative_error &&
          (worst < 0 ||
           result.relative_error[l] > result.relative_error[worst]))
        worst = l;
    }
    if (worst < 0) break;
    result.accepted[worst] = false;
    result.reason[worst] = "it disagrees with the other links of its part by " +
                           Percent(result.relative_error[worst]) +
                           " of the viewing distance (limit " +
                           Percent(options.max_relative_error) + ")";
    if (round + 1 == options.max_rounds) {
      PlaceAlongSpanningTree(links, result.accepted, &result);
      AverageOverLinks(links, result.accepted, options, &result);
      MeasureLinks(links, &result);
    }
  }
  for (size_t l = 0; l < links.size(); ++l) {
    if (result.accepted[l])
      result.reason[l] = "it fits the averaged placement within " +
                         Percent(result.relative_error[l]) +
                         " of the viewing distance";
  }
  return result;
}

}  // namespace tmr
