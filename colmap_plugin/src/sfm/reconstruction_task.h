// Copyright (c) 2026, the tmr authors. BSD-3-Clause.
#pragma once

#include <colmap/controllers/incremental_pipeline.h>
#include <colmap/scene/reconstruction_manager.h>

#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "sfm/match_consistency.h"

namespace tmr {

struct ReconstructionTaskResult {
  bool success = false;
  int num_images = 0;      // images of the task database
  int num_registered = 0;  // registered in the output model
  double seconds = 0.0;
  std::string message;  // why it failed, or which initial pair worked
  // Models of the images the main model could not register, written to
  // output_model + "_part1", "_part2", ...
  std::vector<std::string> part_models;
  int num_registered_in_parts = 0;
};

// The models of a COLMAP mapper run with multiple_models, largest first,
// each image in one model only. COLMAP lets its models share up to
// Mapper.max_model_overlap images; a later (smaller) model here drops the
// images an earlier one holds (their observations leave its tracks).
std::vector<std::shared_ptr<colmap::Reconstruction>> DisjointModels(
    colmap::ReconstructionManager& manager);

// One reconstruction task of the TMR-tree (paper Sec. 5): COLMAP's
// IncrementalPipeline on the task's own database, producing one
// model written to `output_model` (through a temporary folder, renamed when
// complete).
//
// Kernel task: no base model; the first two initial pairs are tried in
// order (the exemplar with COLMAP's choice of a second image, then with
// ours; -1 lets COLMAP choose), then COLMAP's automatic choice; the best
// model wins, and a model with half of the images ends the search. When the
// winner leaves images out, COLMAP's mapper then reconstructs those on their
// own (several models if need be): a kernel can hold two dense groups that
// only its full scene links, and their models may still merge later. The
// largest of these becomes the kernel's model when it is larger than the
// winner (COLMAP keeps the first model of a run whatever its size, and a
// seeded model can stall at a few images). With `kernel_check`, a kernel model
// that contradicts its verified matches is mapped again, with the intrinsics
// held at their priors and then from the other initial pairs, until a redo
// passes (CheckMatchConsistency; the result's message says what happened).
//
// Leaf task: `base_model` is the kernel's model; the mapper extends a copy of
// it with the task's other images, keeping the base poses fixed when
// mapper_options.fix_existing_images is set. Leaf images linked to the
// kernel only through other leaf images cannot be registered when those
// see no point of the base in common (a registered image needs points that
// two registered images see): the images it leaves are reconstructed on
// their own as for a kernel (docs/benchmarks.md, "What fixed city4").
// `halo_images` (images of other clusters, tmr/partition/cluster_halo.h)
// are registered where they fit and never mapped from scratch: their own
// cluster's tasks map them.
ReconstructionTaskResult RunReconstructionTask(
    const colmap::IncrementalPipelineOptions& mapper_options,
    const std::string& task_database, const std::string& base_model,
    const std::vector<std::pair<int, int>>& initial_pairs,
    const MatchConsistencyOptions* kernel_check,
    const std::string& output_model,
    const std::vector<colmap::image_t>& halo_images = {});

// A finished task's result on disk (a small text file, written atomically
// after the task's models), so that a rerun of a killed run can reuse it.
bool SaveTaskResult(const ReconstructionTaskResult& result,
                    const std::string& path);
// False when `path` is missing or not a complete record, or when a model it
// names is missing.
bool LoadTaskResult(const std::string& path, ReconstructionTaskResult* result);

}  // namespace tmr
