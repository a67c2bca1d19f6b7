// Copyright (c) 2026, the tmr authors. BSD-3-Clause.
#include "tmr/partition/exemplar.h"

#include <algorithm>
#include <cmath>
#include <random>
#include <stdexcept>
#include <unordered_map>

namespace tmr {

void AffinityPropagationOptions::AddTo(OptionTable* t) {
  t->Add("Tmr.ap_damping", &damping, "affinity propagation damping")
      .AtLeast(0.5)
      .Below(1);
  t->Add("Tmr.ap_max_iterations", &max_iterations,
         "affinity propagation: most iterations")
      .AtLeast(1);
  t->Add("Tmr.ap_convergence_iterations", &convergence_iterations,
         "affinity propagation: iterations without change that end it")
      .AtLeast(1);
}

bool AffinityPropagationOptions::Check(std::string* error) const {
  return CheckOptionRows(*this, error);
}

void ExemplarOptions::AddTo(OptionTable* t) {
  t->Add("Tmr.beta1", &beta1,
         "weight of the mean similarity in the exemplar score")
      .AtLeast(0);
  t->Add("Tmr.beta2", &beta2,
         "weight of the mean neighbour degree in the exemplar score")
      .AtLeast(0);
  t->Add("Tmr.num_second_images", &num_second_images,
         "second initial images kept as fall-backs")
      .AtLeast(1);
  ap.AddTo(t);
}

bool ExemplarOptions::Check(std::string* error) const {
  return CheckOptionRows(*this, error);
}

std::vector<int> AffinityPropagation(
    std::vector<double> s, int n, const AffinityPropagationOptions& options) {
  if (n <= 0) return {};
  if (n == 1) return {0};
  // Tiny seeded noise removes degenerate ties (as Frey & Dueck do).
  std::mt19937_64 rng(options.seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (double& value : s)
    value += 1e-12 * (std::abs(value) + 1e-9) * unit(rng) + 1e-14 * unit(rng);

  std::vector<double> r(n * n, 0.0), a(n * n, 0.0);
  std::vector<int> exemplars, previous;
  int stable = 0;
  const double lambda = options.damping;
  for (int iteration = 0; iteration < options.max_iterations; ++iteration) {
    // Responsibilities r(i,k) = s(i,k) - max_{k' != k} (a(i,k') + s(i,k')).
    for (int i = 0; i < n; ++i) {
      double first = -INFINITY, second = -INFINITY;
      int first_k = -1;
      for (int k = 0; k < n; ++k) {
        const double value = a[i * n + k] + s[i * n + k];
        if (value > first) {
          second = first, first = value, first_k = k;
        } else if (value > second) {
          second = value;
        }
      }
      for (int k = 0; k < n; ++k) {
        const double target = s[i * n + k] - (k == first_k ? second : first);
        r[i * n + k] = lambda * r[i * n + k] + (1 - lambda) * target;
      }
    }
    // Availabilities a(i,k) = min(0, r(k,k) + sum_{i' not in {i,k}} max(0,
    // r(i',k))), a(k,k) = sum_{i' != k} max(0, r(i',k)).
    for (int k = 0; k < n; ++k) {
      double sum_positive = 0.0;
      for (int i = 0; i < n; ++i) {
        if (i != k) sum_positive += std::max(0.0, r[i * n + k]);
      }
      for (int i = 0; i < n; ++i) {
        const double target =
            i == k ? sum_positive
                   : std::min(0.0, r[k * n + k] + sum_positive -
                                       std::max(0.0, r[i * n + k]));
        a[i * n + k] = lambda * a[i * n + k] + (1 - lambda) * target;
      }
    }
    exemplars.clear();
    for (int k = 0; k < n; ++k) {
      if (a[k * n + k] + r[k * n + k] > 0) exemplars.push_back(k);
    }
    stable = (!exemplars.empty() && exemplars == previous) ? stable + 1 : 0;
    if (stable >= options.convergence_iterations) break;
    previous = exemplars;
  }
  if (exemplars.empty()) {
    int best = 0;
    for (int k = 1; k < n; ++k) {
      if (a[k * n + k] + r[k * n + k] > a[best * n + best] + r[best * n + best])
        best = k;
    }
    exemplars.push_back(best);
  }
  return exemplars;
}

double ExemplarScore(const ImageGraph& similarity, int v, double beta1,
                     double beta2) {
  const auto [begin, end] = similarity.Neighbors(v);
  const int degree = static_cast<int>(end - begin);
  if (degree == 0) return 0.0;
  double sum_similarity = 0.0, sum_neighbour_degree = 0.0;
  for (auto* it = begin; it != end; ++it) {
    sum_similarity += it->weight;
    sum_neighbour_degree += similarity.Degree(it->vertex);
  }
  return degree + beta1 * sum_similarity / degree +
         beta2 * sum_neighbour_degree / degree;
}

KernelSeed SelectExemplar(const ImageGraph& similarity,
                          const MatchGraph& match_graph,
                          const std::vector<int>& kernel,
                          const ExemplarOptions& options) {
  std::string error;
  if (!options.Check(&error))
    throw std::invalid_argument("ExemplarOptions: " + error);
  KernelSeed seed;
  const int n = static_cast<int>(kernel.size());
  if (n == 0) return seed;
  std::unordered_map<int, int> position;
  for (int i = 0; i < n; ++i) position[kernel[i]] = i;

  // Dense similarities of the kernel; preference = median off-diagonal value.
  std::vector<double> s(n * n, 0.0);
  for (int i = 0; i < n; ++i) {
    const auto [begin, end] = similarity.Neighbors(kernel[i]);
    for (auto* it = begin; it != end; ++it) {
      const auto found = position.find(it->vertex);
      if (found != position.end()) s[i * n + found->second] = it->weight;
    }
  }
  std::vector<double> off_diagonal;
  for (int i = 0; i < n; ++i) {
    for (int k = 0; k < n; ++k) {
      if (i != k) off_diagonal.push_back(s[i * n + k]);
    }
  }
  double preference = 0.0;
  if (!off_diagonal.empty()) {
    std::nth_element(off_diagonal.begin(),
                     off_diagonal.begin() + off_diagonal.size() / 2,
                     off_diagonal.end());
    preference = off_diagonal[off_diagonal.size() / 2];
  }
  for (int i = 0; i < n; ++i) s[i * n + i] = preference;
  for (const int centre : AffinityPropagation(std::move(s), n, options.ap)) {
    seed.ap_centres.push_back(kernel[centre]);
  }

  // Candidates: the centres and their neighbours inside the kernel.
  std::vector<int> candidates = seed.ap_centres;
  for (const int centre : seed.ap_centres) {
    const auto [begin, end] = similarity.Neighbors(centre);
    for (auto* it = begin; it != end; ++it) {
      if (position.count(it->vertex)) candidates.push_back(it->vertex);
    }
  }
  std::sort(candidates.begin(), candidates.end());
  candidates.erase(std::unique(candidates.begin(), candidates.end()),
                   candidates.end());
  seed.score = -1.0;
  for (const int v : candidates) {
    const double score =
        ExemplarScore(similarity, v, options.beta1, options.beta2);
    if (score > seed.score) seed.score = score, seed.exemplar = v;
  }

  // Second images: kernel neighbours by n_ij * (1 - s_ij).
  std::unordered_map<int, int> inliers;
  for (const MatchGraphPair& pair : match_graph.pairs) {
    if (pair.image1 == seed.exemplar) inliers[pair.image2] = pair.num_inliers;
    if (pair.image2 == seed.exemplar) inliers[pair.image1] = pair.num_inliers;
  }
  std::vector<std::pair<double, int>> ranked;
  const auto [begin, end] = similarity.Neighbors(seed.exemplar);
  for (auto* it = begin; it != end; ++it) {
    if (!position.count(it->vertex)) continue;
    ranked.emplace_back(-inliers[it->vertex] * (1.0 - it->weight), it->vertex);
  }
  std::sort(ranked.begin(), ranked.end());
  for (size_t k = 0;
       k < ranked.size() && static_cast<int>(k) < options.num_second_images;
       ++k) {
    seed.second_images.push_back(ranked[k].second);
  }
  return seed;
}

}  // namespace tmr
