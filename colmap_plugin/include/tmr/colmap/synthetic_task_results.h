// Copyright (c) 2026, the tmr authors. BSD-3-Clause.
#pragma once

#include <cstdint>
#include <functional>
#include <string>

#include "tmr/colmap/tmr_mapper.h"
#include "tmr/util/option_table.h"

namespace tmr {

// How far the generated task models stray from the ground truth, as a
// mapper's models do.
struct SyntheticTaskResultsOptions {
  // Standard deviation of each image's rotation error, degrees.
  double rotation_noise_deg = 0.02;
  // Standard deviation of each camera centre's and each point's position
  // error, per axis, as a share of the scene's median viewing distance.
  double position_noise = 0.001;
  // Seed of the noise and of each model's frame.
  uint64_t seed = 0;

  // Lists the options as rows of tmr_synth_tasks' command line.
  void AddTo(OptionTable* table);
  bool Check(std::string* error = nullptr) const;
};

// Writes the result of every unfinished kernel and leaf task of the plan in
// options.output_path (PlanTmrMapper) from a ground-truth model whose images
// have the database's ids (tmr_synth's --model_path), as the tasks would
// leave them in the work folder, so that MergeTmrMapper measures the merge
// stage alone, at sizes where running the tasks would take days.
// Each model registers all of its task's images: a kernel task its kernel,
// a leaf task its kernel (with the kernel model's poses, as leaf tasks hold
// them), its leaf cluster and its halo. Poses and points carry Gaussian
// noise (`noise`), and every model is expressed in a random similarity
// frame of its own (COLMAP normalises each model). A point is kept where
// two or more of the model's images observe it. Deterministic for a seed.
// False with `error` when there is no plan or the ground truth does not
// match the database.
bool WriteTaskResultsFromGroundTruth(
    const TmrMapperOptions& options, const std::string& ground_truth_path,
    const SyntheticTaskResultsOptions& noise, std::string* error,
    const std::function<void(const std::string&)>& progress = nullptr);

}  // namespace tmr
