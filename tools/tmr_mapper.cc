// Copyright (c) 2026, the tmr authors. BSD-3-Clause.
// tmr_mapper --database_path DB --image_path IMAGES --output_path OUT:
// the drop-in replacement for `colmap mapper`, reconstructing on the
// TMR-tree. COLMAP's --Mapper.* options pass through; tmr's are --Tmr.*.
#include <boost/program_options.hpp>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>

#include "partition_picture.h"
#include "tmr/colmap/tmr_mapper.h"
#include "tmr_options.h"

namespace fs = std::filesystem;
namespace po = boost::program_options;

int main(int argc, char** argv) {
  tmr::TmrMapperOptions o;
  // Kernels must seed stable models: m >= 30 even in small scenes.
  o.tree.kernels.kernel_size_floor = 30;
  bool verbose = false;
  po::options_description desc(
      "tmr_mapper: COLMAP's incremental mapper on the TMR-tree");
  auto add = [&desc](const char* name, auto* value, const char* help) {
    tmr::AddOption(&desc, name, value, help);
  };
  desc.add_options()("help,h", "print this help")(
      "database_path", po::value(&o.database_path)->required(),
      "COLMAP database (read-only)")(
      "image_path", po::value(&o.image_path),
      "images (optional: colours are skipped without)")(
      "output_path", po::value(&o.output_path)->required(),
      "folder for the models 0, 1, ...");
  add("verbose", &verbose, "show COLMAP's own log");
  add("Mapper.num_threads", &o.num_threads, "threads (-1: all cores)");
  add("Mapper.min_num_matches", &o.mapper.min_num_matches,
      "inliers for a pair to count");
  add("Mapper.ignore_watermarks", &o.mapper.ignore_watermarks,
      "ignore watermark pairs");
  add("Mapper.init_min_num_inliers", &o.mapper.init_min_num_inliers,
      "initial pair inliers");
  add("Mapper.abs_pose_min_num_inliers", &o.mapper.abs_pose_min_num_inliers,
      "PnP inliers");
  add("Mapper.filter_max_reproj_error", &o.mapper.filter_max_reproj_error,
      "max reprojection error");
  add("Mapper.tri_min_angle", &o.mapper.tri_min_angle,
      "min triangulation angle");
  add("Mapper.ba_refine_focal_length", &o.mapper.ba_refine_focal_length,
      "refine focal lengths");
  add("Mapper.ba_refine_principal_point", &o.mapper.ba_refine_principal_point,
      "refine principal points");
  add("Mapper.ba_refine_extra_params", &o.mapper.ba_refine_extra_params,
      "refine distortion");
  add("Mapper.ba_global_max_num_iterations",
      &o.mapper.ba_global_max_num_iterations, "global BA iterations");
  add("Tmr.fix_base_in_leaves", &o.fix_base_in_leaves,
      "keep kernel poses fixed in leaf tasks");
  add("Tmr.merge_min_shared_tracks", &o.merge_min_shared_tracks,
      "tau of the merge rule");
  add("Tmr.refine_merged_models", &o.refine_merged_models,
      "global bundle adjustment after merges");
  add("Tmr.complete_models", &o.complete_models,
      "finally register images no model holds");
  add("Tmr.keep_work", &o.keep_work,
      "keep task databases and models in OUT/.tmr_work");
  tmr::AddTmrTreeOptions(&desc, &o.tree);
  po::variables_map vm;
  if (const auto exit_code =
          tmr::ParseCommandLine("tmr_mapper", argc, argv, desc, &vm)) {
    return *exit_code;
  }
  std::string error;
  if (!o.Check(&error)) {
    std::cerr << "tmr_mapper: error: " << error << "\n";
    return 2;
  }
  tmr::ConfigureColmapLogging(argv[0], verbose);
  const auto start = std::chrono::steady_clock::now();
  auto progress = [&](const std::string& line) {
    const double t =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start)
            .count();
    std::cout << "[tmr " << std::fixed << std::setprecision(1) << std::setw(7)
              << t << " s] " << line << std::endl;
  };
  tmr::TmrMapperReport report;
  try {
    // project.ini: the effective options, as COLMAP writes them.
    fs::create_directories(o.output_path);
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
        ini << *d;
      else if (auto* b = boost::any_cast<bool>(&value))
        ini << (*b ? 1 : 0);
      else if (auto* u = boost::any_cast<uint64_t>(&value))
        ini << *u;
      ini << "\n";
    }
    tmr::WriteFileAtomically((fs::path(o.output_path) / "project.ini").string(),
                             ini.str());
    if (!tmr::RunTmrMapper(o, &report, &error, progress)) {
      std::cerr << "tmr_mapper: error: " << error << "\n";
      return 1;
    }
    // The partition picture, from the tree just written.
    const tmr::MatchGraph graph =
        tmr::ReadMatchGraph(o.database_path, o.match_graph);
    std::vector<std::string> names;
    for (const auto& image : graph.images) names.push_back(image.name);
    std::ifstream tree_file(fs::path(o.output_path) / "tree.json");
    const tmr::TmrTree tree = tmr::ReadTmrTreeJson(tree_file, names);
    tmr::DrawPartitionPicture(
        tmr::BuildSimilarityGraph(graph), tree,
        (fs::path(o.output_path) / "partition.png").string());
  } catch (const std::exception& e) {
    std::cerr << "tmr_mapper: error: " << e.what() << "\n";
    return 1;
  }
  std::cout << "tmr_mapper: " << report.num_images << " images, "
            << report.model_sizes.size() << " models (registered:";
  for (const int size : report.model_sizes) std::cout << " " << size;
  std::cout << ") in " << std::setprecision(1) << report.total_seconds
            << " s\n";
  return 0;
}
