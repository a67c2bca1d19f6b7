// Copyright (c) 2026, the tmr authors. BSD-3-Clause.
// The option rows of tmr_mapper (tmr/util/option_table.h), their Check, and
// their conversion to COLMAP's options.
#include "controllers/tmr_mapper_options.h"

#include <algorithm>
#include <limits>

namespace tmr {

void MapperPassThroughOptions::AddTo(OptionTable* t) {
  auto add = [t](const char* name, auto* value, const char* help) -> auto& {
    return t->Add(name, value, help).ChangesTasks();
  };
  add("Mapper.min_num_matches", &min_num_matches, "inliers for a pair to count")
      .AtLeast(1);
  add("Mapper.ignore_watermarks", &ignore_watermarks, "ignore watermark pairs");
  add("Mapper.init_min_num_inliers", &init_min_num_inliers,
      "initial pair inliers")
      .AtLeast(1);
  add("Mapper.min_model_size", &min_model_size,
      "with several models, drop those with fewer images")
      .AtLeast(1);
  add("Mapper.init_max_forward_motion", &init_max_forward_motion,
      "initial pair: largest forward share of the motion")
      .AtLeast(0)
      .AtMost(1);
  add("Mapper.init_min_tri_angle", &init_min_tri_angle,
      "initial pair: smallest median triangulation angle (deg)")
      .AtLeast(0)
      .Below(180);
  add("Mapper.filter_min_tri_angle", &filter_min_tri_angle,
      "smallest triangulation angle of a kept point (deg)")
      .AtLeast(0)
      .Below(180);
  add("Mapper.abs_pose_min_num_inliers", &abs_pose_min_num_inliers,
      "PnP inliers")
      .AtLeast(1);
  add("Mapper.filter_max_reproj_error", &filter_max_reproj_error,
      "max reprojection error")
      .Above(0);
  add("Mapper.tri_min_angle", &tri_min_angle, "min triangulation angle")
      .Above(0)
      .Below(180);
  add("Mapper.ba_refine_focal_length", &ba_refine_focal_length,
      "refine focal lengths");
  add("Mapper.ba_refine_principal_point", &ba_refine_principal_point,
      "refine principal points");
  add("Mapper.ba_refine_extra_params", &ba_refine_extra_params,
      "refine distortion");
  add("Mapper.ba_global_max_num_iterations", &ba_global_max_num_iterations,
      "global BA iterations")
      .AtLeast(1);
  add("Mapper.ba_global_max_refinements", &ba_global_max_refinements,
      "global BA rounds with re-triangulation")
      .AtLeast(1);
  add("Mapper.ba_global_function_tolerance", &ba_global_function_tolerance,
      "global BA: relative cost change that ends it (0: off)")
      .AtLeast(0);
  add("Mapper.ba_local_num_images", &ba_local_num_images,
      "local BA: images adjusted")
      .AtLeast(2);
  add("Mapper.ba_local_max_num_iterations", &ba_local_max_num_iterations,
      "local BA iterations")
      .AtLeast(1);
  add("Mapper.ba_local_max_refinements", &ba_local_max_refinements,
      "local BA rounds with re-triangulation")
      .AtLeast(1);
  add("Mapper.ba_local_function_tolerance", &ba_local_function_tolerance,
      "local BA: relative cost change that ends it (0: off)")
      .AtLeast(0);
}

void TmrTaskOptions::AddTo(OptionTable* t) {
  t->Add("Tmr.repeatable", &repeatable,
         "each COLMAP step on one thread: the same seed gives the same models")
      .ChangesTasks();
  t->Add("Tmr.fix_base_in_leaves", &fix_base_in_leaves,
         "keep kernel poses fixed in leaf tasks")
      .ChangesTasks();
  t->Add("Tmr.task_ba_global_ratio", &ba_global_ratio,
         "model growth between global BAs in tasks (COLMAP: 1.1)")
      .Above(1)
      .ChangesTasks();
  t->Add("Tmr.check_kernels", &check_kernels,
         "redo a kernel its verified matches contradict, intrinsics held")
      .ChangesTasks();
}

void TmrMergeOptions::AddTo(OptionTable* t) {
  t->Add("Tmr.merge_min_shared_tracks", &min_shared_tracks,
         "tau of the merge rule")
      .AtLeast(3);
  t->Add("Tmr.merge_register_images", &register_images,
         "align by registering this many images on a scene (0: off)")
      .AtLeast(0);
  t->Add("Tmr.merge_align_all_at_once", &align_all_at_once,
         "align all cluster models at once (similarity averaging)");
  t->Add("Tmr.complete_models", &complete_models,
         "finally register images no model holds");
  t->Add("Tmr.merge_max_group_images", &max_group_images,
         "merge by parts in groups of at most this many photos (0: only "
         "when the memory budget needs it)")
      .AtLeast(0);
  t->Add("Tmr.merge_adjust_join", &adjust_join,
         "merge by parts: adjust every pose of the joined scene on the "
         "groups' longest tracks");
}

void TmrRefinementOptions::AddTo(OptionTable* t) {
  t->Add("Tmr.refine_merged_models", &enabled,
         "global bundle adjustment after merges");
  t->Add("Tmr.merge_refine_growth", &growth,
         "refine a scene whenever merges grew it by this factor")
      .AtLeast(1);
  t->Add("Tmr.merge_refine_points_per_image", &points_per_image,
         "those refinements on this many longest tracks per image (0: all)")
      .AtLeast(0);
  t->Add("Tmr.ba_max_block_images", &max_block_images,
         "adjust larger merged models by blocks of this many (0: whole)")
      .AtLeast(0);
  t->Add("Tmr.ba_parallel_block_images", &parallel_block_images,
         "a scene merged at once: its full adjustment as blocks of this "
         "many side by side (0: whole)")
      .AtLeast(0);
}

void TmrMapperOptions::AddTo(OptionTable* t) {
  t->Add("Mapper.num_threads", &num_threads, "threads (-1: all cores)")
      .RunSetting();
  mapper.AddTo(t);
  task.AddTo(t);
  merge.AddTo(t);
  refinement.AddTo(t);
  t->Add(
       "Tmr.memory_budget", &memory_budget,
       "memory every step must fit, GiB (0: half of what the process may use)")
      .AtLeast(0)
      .RunSetting();
  t->Add("Tmr.resume", &resume,
         "reuse the tasks a killed run into OUT finished")
      .RunSetting();
  t->Add("Tmr.keep_work", &keep_work,
         "keep task databases and models in OUT/.tmr_work")
      .RunSetting();
  tree.AddTo(t);
}

bool TmrMapperOptions::Check(std::string* error) const {
  auto fail = [&](const std::string& message) {
    if (error) *error = message;
    return false;
  };
  if (database_path.empty()) return fail("database_path is empty");
  if (output_path.empty()) return fail("output_path is empty");
  if (!CheckOptionRows(*this, error)) return false;
  if (num_threads == 0 || num_threads < -1)
    return fail("Mapper.num_threads must be -1 or >= 1");
  return match_graph.Check(error) && tree.Check(error);
}

int ColmapSeed(uint64_t seed) {
  return static_cast<int>(seed % std::numeric_limits<int>::max());
}

colmap::IncrementalPipelineOptions ColmapOptions(
    const TmrMapperOptions& options, int num_threads) {
  const MapperPassThroughOptions& m = options.mapper;
  colmap::IncrementalPipelineOptions o;
  o.min_num_matches = m.min_num_matches;
  o.ignore_watermarks = m.ignore_watermarks;
  o.min_model_size = m.min_model_size;
  o.mapper.init_min_num_inliers = m.init_min_num_inliers;
  o.mapper.abs_pose_min_num_inliers = m.abs_pose_min_num_inliers;
  o.mapper.init_max_forward_motion = m.init_max_forward_motion;
  o.mapper.init_min_tri_angle = m.init_min_tri_angle;
  o.mapper.filter_min_tri_angle = m.filter_min_tri_angle;
  o.mapper.filter_max_reproj_error = m.filter_max_reproj_error;
  o.triangulation.min_angle = m.tri_min_angle;
  o.ba_refine_focal_length = m.ba_refine_focal_length;
  o.ba_refine_principal_point = m.ba_refine_principal_point;
  o.ba_refine_extra_params = m.ba_refine_extra_params;
  o.ba_global_max_num_iterations = m.ba_global_max_num_iterations;
  o.ba_global_max_refinements = m.ba_global_max_refinements;
  o.ba_global_function_tolerance = m.ba_global_function_tolerance;
  o.mapper.ba_local_num_images = m.ba_local_num_images;
  o.ba_local_max_num_iterations = m.ba_local_max_num_iterations;
  o.ba_local_max_refinements = m.ba_local_max_refinements;
  o.ba_local_function_tolerance = m.ba_local_function_tolerance;
  o.num_threads = options.task.repeatable ? 1 : num_threads;
  o.random_seed = ColmapSeed(options.tree.seed);
  return o;
}

MergedModelAdjustment MergedAdjustment(const TmrMapperOptions& options,
                                       bool while_merging) {
  MergedModelAdjustment adjustment;
  adjustment.enabled = options.refinement.enabled;
  adjustment.max_block_images = options.refinement.max_block_images;
  if (while_merging)
    adjustment.longest_tracks_per_image = options.refinement.points_per_image;
  else
    adjustment.max_refinements = options.mapper.ba_global_max_refinements;
  return adjustment;
}

SceneAssemblyOptions AssemblyOptions(const TmrMapperOptions& options,
                                     int num_threads) {
  SceneAssemblyOptions o;
  o.mapper = ColmapOptions(options, num_threads);
  o.growing_adjustment = MergedAdjustment(options, /*while_merging=*/true);
  o.merged_adjustment = MergedAdjustment(options, /*while_merging=*/false);
  o.min_shared_tracks = options.merge.min_shared_tracks;
  o.register_images = options.merge.register_images;
  o.seed = static_cast<unsigned>(options.tree.seed);
  o.align_all_at_once = options.merge.align_all_at_once;
  o.complete_models = options.merge.complete_models;
  o.refinement_growth = options.refinement.growth;
  o.parallel_block_images = static_cast<size_t>(
      std::max(0, options.refinement.parallel_block_images));
  o.num_threads = num_threads;
  return o;
}

}  // namespace tmr
