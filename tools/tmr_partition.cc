// Copyright (c) 2026, the tmr authors. BSD-3-Clause.
// tmr_partition --database_path DB --output_path DIR: builds the TMR-tree of
// a COLMAP database (read-only) and writes DIR/tree.json and
// DIR/partition.png, then prints a summary.
#include <boost/program_options.hpp>

#include <filesystem>
#include <iostream>

#include "command_line.h"
#include "drawing/partition_picture.h"
#include "tmr/io/database_reader.h"
#include "tmr/partition/tmr_tree.h"
#include "tree_summary.h"

namespace fs = std::filesystem;
namespace po = boost::program_options;

int main(int argc, char** argv) {
  std::string database_path, output_path;
  bool picture = true;
  tmr::MatchGraphOptions graph_options;
  tmr::TmrTreeOptions tree_options;
  po::options_description desc(
      "tmr_partition: the TMR-tree of a COLMAP database");
  desc.add_options()("help,h", "print this help")(
      "database_path", po::value(&database_path)->required(),
      "COLMAP database (read-only)")("output_path",
                                     po::value(&output_path)->required(),
                                     "folder for tree.json and partition.png")(
      "min_num_matches",
      po::value(&graph_options.min_num_matches)
          ->default_value(graph_options.min_num_matches),
      "minimum inlier matches of a pair")(
      "picture", po::value(&picture)->default_value(picture),
      "draw partition.png");
  tmr::AddOptionsOf(&desc, &tree_options);
  po::variables_map vm;
  if (const auto exit_code =
          tmr::ParseCommandLine("tmr_partition", argc, argv, desc, &vm)) {
    return *exit_code;
  }
  std::string error;
  if (!tree_options.Check(&error) || !graph_options.Check(&error)) {
    std::cerr << "tmr_partition: error: " << error << "\n";
    return 2;
  }
  try {
    const tmr::DatabasePartition partition =
        tmr::PartitionDatabase(database_path, graph_options, tree_options);
    std::cout << "read " << partition.graph.NumImages() << " images and "
              << partition.graph.NumPairs() << " verified pairs in "
              << partition.read_seconds << " s\n";
    std::error_code ec;
    fs::create_directories(output_path, ec);
    if (ec) {
      throw std::runtime_error("cannot create output folder '" + output_path +
                               "': " + ec.message());
    }
    const std::string tree_path = tmr::TmrTreeJsonPath(output_path);
    if (!tmr::WriteTmrTreeJsonFile(partition.tree, output_path))
      throw std::runtime_error("cannot write '" + tree_path + "'");
    tmr::PrintTreeSummary(partition.tree, std::cout);
    std::cout << "wrote " << tree_path << "\n";
    if (picture) {
      const std::string png =
          (fs::path(output_path) / "partition.png").string();
      if (!tmr::DrawPartitionPicture(tmr::BuildSimilarityGraph(partition.graph),
                                     partition.tree, png)) {
        throw std::runtime_error("cannot write '" + png + "'");
      }
      std::cout << "wrote " << png << "\n";
    }
  } catch (const std::exception& e) {
    std::cerr << "tmr_partition: error: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
