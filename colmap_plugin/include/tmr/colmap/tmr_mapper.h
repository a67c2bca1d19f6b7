// Copyright (c) 2026, the tmr authors. BSD-3-Clause.
#pragma once

#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "tmr/colmap/task_report.h"
#include "tmr/io/database_reader.h"
#include "tmr/partition/tmr_tree.h"
#include "tmr/util/option_table.h"

namespace tmr {

// COLMAP mapper options that tmr_mapper passes through (--Mapper.*); the
// defaults are COLMAP's.
struct MapperPassThroughOptions {
  int min_num_matches = 15;        // --Mapper.min_num_matches
  bool ignore_watermarks = false;  // --Mapper.ignore_watermarks
  int init_min_num_inliers = 100;  // --Mapper.init_min_num_inliers
  // With several models, smaller ones are dropped (their photos stay
  // unregistered); at most 80% of the images, as in COLMAP.
  int min_model_size = 10;  // --Mapper.min_model_size
  // Initial pair: at most this forward share of the motion (|t_z|), at
  // least this median triangulation angle (degrees). Photos taken walking
  // straight ahead need 1 and a few degrees.
  double init_max_forward_motion = 0.95;   // --Mapper.init_max_forward_motion
  double init_min_tri_angle = 16.0;        // --Mapper.init_min_tri_angle
  double filter_min_tri_angle = 1.5;       // --Mapper.filter_min_tri_angle
  int abs_pose_min_num_inliers = 30;       // --Mapper.abs_pose_min_num_inliers
  double filter_max_reproj_error = 4.0;    // --Mapper.filter_max_reproj_error
  double tri_min_angle = 1.5;              // --Mapper.tri_min_angle
  bool ba_refine_focal_length = true;      // --Mapper.ba_refine_focal_length
  bool ba_refine_principal_point = false;  // --Mapper.ba_refine_principal_point
  bool ba_refine_extra_params = true;      // --Mapper.ba_refine_extra_params
  // COLMAP's adjustments, --Mapper.ba_* of the same names. A function
  // tolerance ends an adjustment at that relative cost change (0: run to
  // the iteration limit or the gradient tolerance, as COLMAP does).
  int ba_global_max_num_iterations = 50;
  int ba_global_max_refinements = 5;
  double ba_global_function_tolerance = 0.0;
  int ba_local_num_images = 6;
  int ba_local_max_num_iterations = 25;
  int ba_local_max_refinements = 2;
  double ba_local_function_tolerance = 0.0;

  // Lists the options as --Mapper.* rows (tmr/util/option_table.h); every
  // one changes the tasks.
  void AddTo(OptionTable* table);
};

// What a kernel or leaf task reads besides COLMAP's mapper options; every
// option here changes the tasks (a resumed run redoes them).
struct TmrTaskOptions {
  // Run each COLMAP step (bundle adjustment, structure-less RANSAC) on one
  // thread; tasks still run side by side on num_threads workers. The same
  // database, options and tree.seed then give byte-identical models in
  // whatever order the tasks finish. With more threads per step, Ceres and
  // COLMAP's parallel RANSAC sum and draw in an order that varies between
  // runs (COLMAP's own repeatability tests use one thread), and a task's
  // share of the threads depends on how many others run beside it.
  bool repeatable = true;  // --Tmr.repeatable
  // Keep the kernel's poses fixed when leaf clusters extend it.
  bool fix_base_in_leaves = true;  // --Tmr.fix_base_in_leaves
  // Growth of a task's model between two of COLMAP's global adjustments
  // (its ba_global_images_ratio and ba_global_points_ratio, 1.1 in COLMAP).
  // Every merged model gets a full global adjustment, so the tasks can
  // afford fewer (figures: docs/benchmarks.md).
  double ba_global_ratio = 2.0;  // --Tmr.task_ba_global_ratio
  // Check every kernel model against its verified matches (triangulated
  // with the model's poses, those no common track holds must reproject
  // within 4 px) and map a kernel that fails once more with its intrinsics
  // held at their priors.
  bool check_kernels = true;  // --Tmr.check_kernels

  // Lists the options as --Tmr.* rows (tmr/util/option_table.h).
  void AddTo(OptionTable* table);
};

// How models are merged: leaf models into their cluster's, cluster models
// into scenes, and what is left over.
struct TmrMergeOptions {
  // tau of the merge rule (paper Sec. 5).
  int min_shared_tracks = 12;  // --Tmr.merge_min_shared_tracks
  // A model that shares too few tracks with a scene for that rule is
  // aligned by registering up to this many of its images on the scene's
  // points (AlignModelsByRegisteredImages); 0: the track rule only.
  int register_images = 10;  // --Tmr.merge_register_images
  // Image-cluster models are aligned all at once: every linked pair in
  // parallel, then one similarity averaging over the graph of models that
  // refuses links inconsistent around loops, and each connected part is
  // appended into its largest model with no refinement between
  // (merge/similarity_averaging.h). false: one model after the other into
  // growing scenes, refined as they grow (--Tmr.merge_refine_growth).
  bool align_all_at_once = true;  // --Tmr.merge_align_all_at_once
  // Finally let COLMAP's mapper continue every model with the images no
  // model holds yet, and map what is still left from scratch.
  bool complete_models = true;  // --Tmr.complete_models
  // A scene of more photos is merged by parts (docs/distributed.md) in
  // groups of clusters of at most about this many photos (a cluster larger
  // alone, halos and unclustered photos added), even where the whole merge
  // fits the memory budget: a group's adjustments cost more per photo the
  // larger it is. 0: by parts only when the budget needs it.
  int max_group_images = 0;  // --Tmr.merge_max_group_images
  // The join of a merge by parts adjusts every pose of each joined scene
  // together on the groups' longest tracks (JoinAdjustment; as many per
  // image as the whole stage's first adjustment,
  // merge_refine_points_per_image, or fewer where the memory budget
  // needs): the groups' own adjustments do not see across their seams, and
  // their similarities move each group as a rigid block. false: placed by
  // similarities only.
  bool adjust_join = true;  // --Tmr.merge_adjust_join

  // Lists the options as --Tmr.* rows (tmr/util/option_table.h).
  void AddTo(OptionTable* table);
};

// Bundle adjustment of merged models.
struct TmrRefinementOptions {
  // Global bundle adjustment of each merged model.
  bool enabled = true;  // --Tmr.refine_merged_models
  // While image-cluster models are merged into a scene, the scene is
  // refined whenever it has grown by this factor since its last global
  // adjustment (and once more at the end).
  double growth = 1.5;  // --Tmr.merge_refine_growth
  // Those refinements while scenes grow adjust every pose on only this many
  // longest tracks per image (AdjustOnLongestTracks): the large-scale shape
  // that the next merges are tested against, at a part of the cost; each
  // scene gets its full adjustment once, at the end. 0: every refinement
  // full.
  int points_per_image = 500;  // --Tmr.merge_refine_points_per_image
  // A merged model of more registered images is fully bundle-adjusted in two
  // smaller problems (AdjustByBlocks): every pose on the 500 longest tracks
  // of each image, then blocks of at most this many images with all their
  // points; 0 adjusts every model whole (most memory). 1,000 is where
  // COLMAP leaves its direct sparse solver.
  int max_block_images = 1000;  // --Tmr.ba_max_block_images
  // A scene merged all at once (merge_align_all_at_once), adjusted first on
  // its longest tracks, gets its full adjustment as blocks of at most this
  // many images adjusted side by side, one per worker, the poses around
  // each block held (AdjustBlocksAtOnce); 0: one adjustment of the whole.
  // Off by default: on plazas8v it left 0.22 deg against 0.07 deg
  // (docs/mapper.md, step 7).
  int parallel_block_images = 0;  // --Tmr.ba_parallel_block_images

  // Lists the options as --Tmr.* rows (tmr/util/option_table.h).
  void AddTo(OptionTable* table);
};

struct TmrMapperOptions {
  std::string database_path;  // read-only
  std::string image_path;     // optional: colours are skipped when empty
  std::string output_path;    // models 0, 1, ... plus tree.json and report
  // Worker threads (-1: all cores); this many tasks run at once.
  int num_threads = -1;  // --Mapper.num_threads
  // Keep the task databases and models in output_path/.tmr_work.
  bool keep_work = false;  // --Tmr.keep_work
  // The memory every step must stay under, in GiB; 0: half of the memory
  // this process may use (the machine's, or a Slurm job's or container's
  // limit). A task expected to need more stops the run before it starts;
  // tasks run side by side only as far as it allows.
  double memory_budget = 0.0;  // --Tmr.memory_budget
  // Reuse the kernel and leaf tasks that a killed run into the same
  // output_path finished (output_path/.tmr_work), when the database, the
  // partition and the task options are the same; otherwise start clean.
  bool resume = true;  // --Tmr.resume
  // Its min_num_matches is taken from mapper.min_num_matches.
  MatchGraphOptions match_graph;
  TmrTreeOptions tree;              // the partition
  MapperPassThroughOptions mapper;  // COLMAP's, in every task
  TmrTaskOptions task;              // kernel and leaf tasks
  TmrMergeOptions merge;            // cluster and scene merges
  TmrRefinementOptions refinement;  // adjustment of merged models

  // Lists every option but the paths as a --Mapper.* or --Tmr.* row, the
  // tree's included (tmr/util/option_table.h): the command line,
  // project.ini and the resume fingerprint (RunFingerprint) read them.
  void AddTo(OptionTable* table);
  bool Check(std::string* error = nullptr) const;
};

struct TmrMapperReport {
  int num_images = 0;
  std::vector<int>
      model_sizes;  // registered images per output model, largest first
  std::vector<TmrTaskReport> tasks;
  std::vector<TmrWeakLink> weak_links;
  double partition_seconds = 0.0;
  double total_seconds = 0.0;
  // Where the wall time went (SummarizeTimeline): when the last task of
  // the task graph ended; the wall time with unlimited workers (what comes
  // before the task graph, its longest chain of dependent rows, and the
  // steps after it); and the recorded rows replayed on 2, 4, 8, 16 and 64
  // workers (workers, projected wall time).
  double tasks_end_s = 0.0;
  double critical_path_s = 0.0;
  std::vector<std::pair<int, double>> projected_wall_s;
  // The workers the run had, and the rows of its longest chain of
  // dependent rows (each part-parallel row counted at its longest part),
  // first to last.
  int num_workers = 0;
  std::vector<int> critical_path_rows;
};

// Reconstructs the database on its TMR-tree (paper Sec. 5): kernels in
// parallel, each seeded at its exemplar; then leaf clusters in parallel,
// each extending a copy of its kernel's model; leaf models are merged into
// image-cluster models, and those into scene models when the merge rule
// finds a reliable similarity; the rest stay separate models. Writes
// output_path/0, 1, ... (largest first, COLMAP binary), tree.json and
// report.json (the tool adds partition.png and project.ini); every model
// appears only when complete.
// `progress` receives one line per finished step. Returns false with a
// reason in `error`.
bool RunTmrMapper(
    const TmrMapperOptions& options, TmrMapperReport* report,
    std::string* error,
    const std::function<void(const std::string&)>& progress = nullptr);

// The staged run, for batch schedulers (docs/distributed.md): the steps of
// RunTmrMapper as separate calls, possibly in other processes on other
// machines that share output_path, each given the options the plan was
// made with. RunTmrMapper is these steps on its own scheduler and gives the
// same models.

// A kernel or leaf-cluster task of the plan.
struct TmrMapperTask {
  std::string id;           // "kernel.K" or "leaf.K.L"
  int kernel = 0;           // K
  int leaf = -1;            // L; -1 for the kernel task
  int num_images = 0;       // the kernel's or leaf cluster's images
  int num_base_images = 0;  // a leaf task also carries its kernel's
  bool finished = false;    // a complete result is on disk
  // The expected peak memory of a process that runs it (MiB).
  double memory_mib = 0.0;
};

// A group of clusters of a merge stage by parts (docs/distributed.md),
// merged on its own once the tasks of its clusters have finished.
struct TmrMergeGroup {
  std::string id;           // "merge.G"
  int num_images = 0;       // its clusters', their halos' and its extra images
  bool ready = false;       // the tasks of its clusters have finished
  bool merged = false;      // its models are in the work folder
  double memory_mib = 0.0;  // the expected peak of its merge
};

// The plan of a staged run: its tasks, and the merge stage after them.
struct TmrMapperPlan {
  std::vector<TmrMapperTask> tasks;
  int num_images = 0;
  // The merge stage's expected peak; by parts, its join's.
  double merge_memory_mib = 0.0;
  // The merge stage by parts: its groups, merged before the join; empty
  // when the merge stage fits the memory budget whole.
  std::vector<TmrMergeGroup> merge_groups;
};

// Stage 1: the TMR-tree (tree.json), the task plan (plan.txt: per line a
// task's id, images, base images and expected memory in MiB; by parts, a
// line per group of the merge stage and one of the seams' images; then
// "merge", all images, 0 and the merge stage's memory) and the work folder
// (output_path/.tmr_work); a plan made again with the same database and
// options keeps the finished tasks. False when a task would not fit
// options.memory_budget.
bool PlanTmrMapper(
    const TmrMapperOptions& options, TmrMapperPlan* plan, std::string* error,
    const std::function<void(const std::string&)>& progress = nullptr);

// The plan in output_path with the state of each task. False when there is
// none, or when it was made from another database or with other options.
bool ReadTmrMapperPlan(const TmrMapperOptions& options, TmrMapperPlan* plan,
                       std::string* error);

// Stage 2: one task by id; a finished task is not run again, so a rerun is
// safe. A leaf task needs its kernel task finished.
bool RunTmrMapperTask(const TmrMapperOptions& options,
                      const std::string& task_id, TmrTaskReport* report,
                      std::string* error);

// Stage 3: cluster merges, scene models and output as RunTmrMapper writes
// them (by parts: the groups not merged yet, then their join); every task
// must have finished.
bool MergeTmrMapper(
    const TmrMapperOptions& options, TmrMapperReport* report,
    std::string* error,
    const std::function<void(const std::string&)>& progress = nullptr);

// Stage 3 by parts, for a scheduler: group `group_id` ("merge.G") of the
// merge stage alone, its models into the work folder (reused when there
// already); MergeTmrMapper then merges the groups not merged yet and joins
// them. False when the plan has no such group or a task of its clusters
// has not finished.
bool MergeTmrMapperGroup(
    const TmrMapperOptions& options, const std::string& group_id,
    std::string* error,
    const std::function<void(const std::string&)>& progress = nullptr);

}  // namespace tmr

namespace tmr {

// Sets up COLMAP's logging (glog) for a command-line tool: to stderr,
// warnings and errors only unless `verbose`.
void ConfigureColmapLogging(const char* program, bool verbose);

}  // namespace tmr
