// Copyright (c) 2026, the tmr authors. BSD-3-Clause.
// Small pieces of tmr_mapper's pipeline: COLMAP option bridging and the run
// report.
#pragma once

#include <colmap/controllers/incremental_pipeline.h>

#include <chrono>
#include <cstdint>
#include <functional>
#include <string>

#include "sfm/model_merging.h"
#include "tmr/colmap/tmr_mapper.h"

namespace tmr {

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

// Hands memory that was freed back to the system (glibc keeps freed memory
// in per-thread arenas: an adjustment run on another worker thread than the
// previous one would otherwise add to the peak). A no-op elsewhere.
void ReleaseFreedMemory();

// Seconds of wall time since `start`.
double SecondsSince(std::chrono::steady_clock::time_point start);

// A hash of the content of a SQLite database file and of its write-ahead
// log, if any. It leaves out the two header counters SQLite rewrites at every
// commit even when no row changed (COLMAP's own tools, hierarchical_mapper
// among them, open the database for writing and do that), and the
// modification time.
uint64_t DatabaseContentHash(const std::string& path);

// What the kernel and leaf tasks of a run depend on: the partition
// (tree.json), the database's content (DatabaseContentHash) and the options
// that change tasks (OptionRow::changes_tasks). A rerun reuses finished
// tasks only when it matches.
std::string RunFingerprint(const TmrMapperOptions& options,
                           const std::string& tree_json);

// The content of a file; empty when it cannot be read.
std::string ReadFileToString(const std::string& path);

// report.json of a run.
std::string ReportJson(const TmrMapperReport& report);

}  // namespace tmr
