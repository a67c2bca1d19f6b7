// Copyright (c) 2026, the tmr authors. BSD-3-Clause.
#pragma once

#include <colmap/geometry/sim3.h>

#include <Eigen/Core>
#include <string>
#include <vector>

namespace tmr {

// A similarity between two models and where it was measured.
struct SimilarityLink {
  int model1 = -1;
  int model2 = -1;
  colmap::Sim3d model1_from_model2;
  // Points of model2 on its seam with model1, in model2's frame: a
  // placement of the two models is judged by how far it moves these points
  // from where the link puts them.
  std::vector<Eigen::Vector3d> points2;
  // The length that disagreement is measured against, in model2's units
  // (the median viewing distance of points2).
  double scale2 = 1.0;
  // How strongly the models are linked (verified matches between them):
  // the spanning tree that starts the averaging takes the strongest links.
  double weight = 1.0;
};

struct SimilarityAveragingOptions {
  // A link whose points the averaged placement puts farther than this share
  // of their viewing distance from where the link puts them (median over
  // its points) disagrees with the other links and is refused. Also the
  // scale of the robust (Cauchy) loss of the averaging.
  double max_relative_error = 0.05;
  // A link that disagrees by more than this share with the path through a
  // third model (its two links composed) breaks that loop. Looser than
  // max_relative_error: the path carries two links' errors, measured away
  // from the seams they were estimated on; a wrong link is off by far more.
  double max_loop_error = 0.15;
  // Rounds of averaging, each refusing the worst link that disagrees.
  int max_rounds = 10;
  // Points of a link used by the averaging (evenly spread over points2).
  int max_points_per_link = 64;

  void Check() const;
};

struct SimilarityAveraging {
  // Per model: the first (lowest) model index of its part (the models that
  // accepted links connect), and its pose in that model's frame.
  std::vector<int> part;
  std::vector<colmap::Sim3d> part_from_model;
  // Per link: whether it holds, its disagreement with the placement (as
  // SimilarityAveragingOptions::max_relative_error measures it; infinite
  // between models of different parts), and in words how well it fits or
  // why it was refused.
  std::vector<bool> accepted;
  std::vector<double> relative_error;
  std::vector<std::string> reason;
};

// Places every model of a graph of pairwise similarities in one frame per
// connected part (the paper's merges are pairwise, Sec. 5). First, loop consistency on
// triangles of links: a link that disagrees with more triangles through it
// than agree is refused, the worst first (a wrong link breaks every loop it
// closes, a right one only the loops that hold a wrong link). Then a
// spanning tree of the strongest links gives the start, and a robust least
// squares over all remaining links (every link's points, moved by both
// models' placements, should meet) spreads the loops' residual error over
// them; a link that still disagrees by more than max_relative_error is
// refused, the worst first, and the averaging repeats. Models that no
// accepted link joins stay apart.
SimilarityAveraging AverageSimilarities(
    int num_models, const std::vector<SimilarityLink>& links,
    const SimilarityAveragingOptions& options);

}  // namespace tmr
