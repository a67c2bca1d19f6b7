// Copyright (c) 2026, the tmr authors. BSD-3-Clause.
#include "mapper_options.h"

#include <chrono>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <sstream>

#include "drawing/partition_picture.h"
#include "tmr_options.h"

namespace tmr {

namespace fs = std::filesystem;
namespace po = boost::program_options;

std::string ProjectIniOfPlan(int argc, char** argv) {
  std::string ini;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    std::string path;
    if (arg == "--plan" && i + 1 < argc) path = argv[i + 1];
    if (arg.rfind("--plan=", 0) == 0) path = arg.substr(7);
    if (!path.empty())
      ini = (fs::path(path).parent_path() / "project.ini").string();
  }
  return ini;
}

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
      ini << ExactDoubleText(*d);
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
  const std::string tree_path = TmrTreeJsonPath(o.output_path);
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
