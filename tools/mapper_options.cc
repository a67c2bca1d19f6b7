// Copyright (c) 2026, the tmr authors. BSD-3-Clause.
#include "mapper_options.h"

#include <chrono>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <sstream>

#include "partition_picture.h"
#include "tmr_options.h"

namespace tmr {

namespace fs = std::filesystem;
namespace po = boost::program_options;

void AddTmrMapperOptions(po::options_description* desc, TmrMapperOptions* o) {
  auto add = [desc](const char* name, auto* value, const char* help) {
    AddOption(desc, name, value, help);
  };
  add("Mapper.num_threads", &o->num_threads, "threads (-1: all cores)");
  add("Tmr.repeatable", &o->repeatable,
      "each COLMAP step on one thread: the same seed gives the same models");
  add("Mapper.min_num_matches", &o->mapper.min_num_matches,
      "inliers for a pair to count");
  add("Mapper.ignore_watermarks", &o->mapper.ignore_watermarks,
      "ignore watermark pairs");
  add("Mapper.init_min_num_inliers", &o->mapper.init_min_num_inliers,
      "initial pair inliers");
  add("Mapper.min_model_size", &o->mapper.min_model_size,
      "with several models, drop those with fewer images");
  add("Mapper.init_max_forward_motion", &o->mapper.init_max_forward_motion,
      "initial pair: largest forward share of the motion");
  add("Mapper.init_min_tri_angle", &o->mapper.init_min_tri_angle,
      "initial pair: smallest median triangulation angle (deg)");
  add("Mapper.filter_min_tri_angle", &o->mapper.filter_min_tri_angle,
      "smallest triangulation angle of a kept point (deg)");
  add("Mapper.abs_pose_min_num_inliers", &o->mapper.abs_pose_min_num_inliers,
      "PnP inliers");
  add("Mapper.filter_max_reproj_error", &o->mapper.filter_max_reproj_error,
      "max reprojection error");
  add("Mapper.tri_min_angle", &o->mapper.tri_min_angle,
      "min triangulation angle");
  add("Mapper.ba_refine_focal_length", &o->mapper.ba_refine_focal_length,
      "refine focal lengths");
  add("Mapper.ba_refine_principal_point", &o->mapper.ba_refine_principal_point,
      "refine principal points");
  add("Mapper.ba_refine_extra_params", &o->mapper.ba_refine_extra_params,
      "refine distortion");
  add("Mapper.ba_global_max_num_iterations",
      &o->mapper.ba_global_max_num_iterations, "global BA iterations");
  add("Mapper.ba_global_max_refinements", &o->mapper.ba_global_max_refinements,
      "global BA rounds with re-triangulation");
  add("Mapper.ba_global_function_tolerance",
      &o->mapper.ba_global_function_tolerance,
      "global BA: relative cost change that ends it (0: off)");
  add("Mapper.ba_local_num_images", &o->mapper.ba_local_num_images,
      "local BA: images adjusted");
  add("Mapper.ba_local_max_num_iterations",
      &o->mapper.ba_local_max_num_iterations, "local BA iterations");
  add("Mapper.ba_local_max_refinements", &o->mapper.ba_local_max_refinements,
      "local BA rounds with re-triangulation");
  add("Mapper.ba_local_function_tolerance",
      &o->mapper.ba_local_function_tolerance,
      "local BA: relative cost change that ends it (0: off)");
  add("Tmr.fix_base_in_leaves", &o->fix_base_in_leaves,
      "keep kernel poses fixed in leaf tasks");
  add("Tmr.merge_min_shared_tracks", &o->merge_min_shared_tracks,
      "tau of the merge rule");
  add("Tmr.merge_register_images", &o->merge_register_images,
      "align by registering this many images on a scene (0: off)");
  add("Tmr.task_ba_global_ratio", &o->task_ba_global_ratio,
      "model growth between global BAs in tasks (COLMAP: 1.1)");
  add("Tmr.check_kernels", &o->check_kernels,
      "redo a kernel its verified matches contradict, intrinsics held");
  add("Tmr.refine_merged_models", &o->refine_merged_models,
      "global bundle adjustment after merges");
  add("Tmr.merge_refine_growth", &o->merge_refine_growth,
      "refine a scene whenever merges grew it by this factor");
  add("Tmr.merge_refine_points_per_image", &o->merge_refine_points_per_image,
      "those refinements on this many longest tracks per image (0: all)");
  add("Tmr.ba_max_block_images", &o->ba_max_block_images,
      "adjust larger merged models by blocks of this many (0: whole)");
  add("Tmr.complete_models", &o->complete_models,
      "finally register images no model holds");
  add("Tmr.resume", &o->resume,
      "reuse the tasks a killed run into OUT finished");
  add("Tmr.keep_work", &o->keep_work,
      "keep task databases and models in OUT/.tmr_work");
  AddTmrTreeOptions(desc, &o->tree);
}

namespace {

// The shortest of 15 to 17 significant digits that reads back as `value`:
// a later stage reads project.ini and must see the same options.
std::string ShortestExact(double value) {
  std::string text;
  for (int digits = 15; digits <= 17; ++digits) {
    std::ostringstream out;
    out.precision(digits);
    out << value;
    text = out.str();
    if (std::stod(text) == value) break;
  }
  return text;
}

}  // namespace

std::string ProjectIni(const po::options_description& desc,
                       const po::variables_map& vm) {
  std::ostringstream ini;
  for (const auto& option : desc.options()) {
    const std::string name = option->long_name();
    if (name == "help" || !vm.count(name)) continue;
    const auto& value = vm[name].value();
    ini << name << "=";
    if (auto* s = boost::any_cast<std::string>(&value))
      ini << *s;
    else if (auto* i = boost::any_cast<int>(&value))
      ini << *i;
    else if (auto* d = boost::any_cast<double>(&value))
      ini << ShortestExact(*d);
    else if (auto* b = boost::any_cast<bool>(&value))
      ini << (*b ? 1 : 0);
    else if (auto* u = boost::any_cast<uint64_t>(&value))
      ini << *u;
    ini << "\n";
  }
  return ini.str();
}

bool DrawMapperPartitionPicture(const TmrMapperOptions& o) {
  // Beyond this size a dot per image is unreadable at 1,600 pixels (the
  // layout itself takes 3 s at 3,752 images and grows as n log n). The
  // tree's size decides before the match graph is read.
  constexpr size_t kMaxPictureImages = 20000;
  const fs::path tree_path = fs::path(o.output_path) / "tree.json";
  std::ifstream tree_file(tree_path);
  if (ReadTmrTreeJson(tree_file).image_names.size() > kMaxPictureImages)
    return false;
  const MatchGraph graph = ReadMatchGraph(o.database_path, o.match_graph);
  std::vector<std::string> names;
  for (const auto& image : graph.images) names.push_back(image.name);
  tree_file.clear();
  tree_file.seekg(0);
  const TmrTree tree = ReadTmrTreeJson(tree_file, names);
  DrawPartitionPicture(BuildSimilarityGraph(graph), tree,
                       (fs::path(o.output_path) / "partition.png").string());
  return true;
}

std::function<void(const std::string&)> TimedProgressLines() {
  const auto start = std::chrono::steady_clock::now();
  return [start](const std::string& line) {
    const double t =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start)
            .count();
    std::cout << "[tmr " << std::fixed << std::setprecision(1) << std::setw(7)
              << t << " s] " << line << std::endl;
  };
}

}  // namespace tmr
