// Copyright (c) 2026, the tmr authors. BSD-3-Clause.
// tmr_mapper's options turned into COLMAP's: the one boundary where
// TmrMapperOptions meet COLMAP's option structs.
#pragma once

#include <colmap/controllers/incremental_pipeline.h>

#include "merge/merged_model_refinement.h"
#include "merge/scene_assembly.h"
#include "tmr/colmap/tmr_mapper.h"

namespace tmr {

// COLMAP's random_seed (an int, -1 meaning "from the clock") for tmr's
// seed: options.tree.seed folded into [0, INT_MAX).
int ColmapSeed(uint64_t seed);

// COLMAP's mapper options with tmr_mapper's pass-through values, seeded
// with options.tree.seed (COLMAP 4's random_seed), on `num_threads` threads
// (one when options.task.repeatable: the same seed then gives the same models).
colmap::IncrementalPipelineOptions ColmapOptions(
    const TmrMapperOptions& options, int num_threads);

// The bundle adjustment of a merged model that the options ask for: the
// full one (an image-cluster model, a scene's last refinement), or, for the
// refinements while scenes grow, on the longest tracks only
// (merge_refine_points_per_image).
MergedModelAdjustment MergedAdjustment(const TmrMapperOptions& options,
                                       bool while_merging);

// SceneAssembler's options (merge/scene_assembly.h) from tmr_mapper's, on
// `num_threads` workers.
SceneAssemblyOptions AssemblyOptions(const TmrMapperOptions& options,
                                     int num_threads);

}  // namespace tmr
