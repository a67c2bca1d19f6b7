// Copyright (c) 2026, the tmr authors. BSD-3-Clause.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "tmr/scene/image_graph.h"
#include "tmr/scene/match_graph.h"
#include "tmr/util/option_table.h"

namespace tmr {

struct AffinityPropagationOptions {
  // Damping lambda of the message updates (Frey & Dueck suggest 0.5 to 0.9;
  // 0.9 avoids the oscillations of small, nearly uniform kernels).
  double damping = 0.9;
  int max_iterations = 1000;
  // Stop when the exemplars stay the same for this many iterations.
  int convergence_iterations = 50;
  // Seed of the tiny noise that breaks ties between equal similarities
  // (TmrTreeOptions::seed; not a row of its own).
  uint64_t seed = 0;

  // Lists the options as --Tmr.ap_* rows (tmr/util/option_table.h).
  void AddTo(OptionTable* table);
  bool Check(std::string* error = nullptr) const;
};

// Affinity propagation (Frey & Dueck, Science 2007) on a dense n x n
// similarity matrix (row-major); the diagonal holds the preferences.
// Returns the exemplars, sorted; never empty for n >= 1.
std::vector<int> AffinityPropagation(std::vector<double> similarity, int n,
                                     const AffinityPropagationOptions& options);

struct ExemplarOptions {
  AffinityPropagationOptions ap;
  // Weights of Eq. 5: delta = deg + beta1 * mean_sim + beta2 * mean_ndeg.
  double beta1 = 100.0;
  double beta2 = 1.0;
  // Second initial images kept as fall-backs, best first.
  int num_second_images = 5;

  // Lists the options (and ap's) as --Tmr.* rows.
  void AddTo(OptionTable* table);
  bool Check(std::string* error = nullptr) const;
};

struct KernelSeed {
  int exemplar = -1;  // vertex index (the reconstruction's first image)
  std::vector<int> second_images;  // best first
  std::vector<int> ap_centres;     // affinity propagation exemplars
  double score = 0.0;              // delta(exemplar)
};

// The exemplar of a kernel (paper Sec. 4.1): affinity propagation on the
// kernel's images with s_ij of Eq. 1 (0 where there is no edge) and the
// median similarity as preference; the AP centres and their neighbours in S
// inside the kernel are the candidates, scored by Eq. 5; the highest score
// wins (ties: smaller index). The second images are the exemplar's kernel
// neighbours ranked by n_ij * (1 - s_ij): many matches, but not a
// near-duplicate view (a proxy for a wide baseline).
KernelSeed SelectExemplar(const ImageGraph& similarity,
                          const MatchGraph& match_graph,
                          const std::vector<int>& kernel,
                          const ExemplarOptions& options);

// delta(v) of Eq. 5 on S.
double ExemplarScore(const ImageGraph& similarity, int v, double beta1,
                     double beta2);

}  // namespace tmr
