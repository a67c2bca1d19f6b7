// Copyright (c) 2026, the tmr authors. BSD-3-Clause.
// tmr_graph_info --database_path DB: reads the verified match graph of a
// COLMAP database (read-only) and prints the similarity graph S of Eq. 1.
#include <boost/program_options.hpp>

#include <chrono>
#include <iostream>

#include "tmr/io/database_reader.h"
#include "tmr/scene/graph_summary.h"
#include "tmr/scene/image_graph.h"

namespace po = boost::program_options;

int main(int argc, char** argv) {
  std::string database_path;
  tmr::MatchGraphOptions options;
  po::options_description desc(
      "tmr_graph_info: summary of the match graph of a COLMAP database");
  desc.add_options()("help,h", "print this help")(
      "database_path", po::value(&database_path)->required(),
      "COLMAP database.db (opened read-only)")(
      "min_num_matches",
      po::value(&options.min_num_matches)
          ->default_value(options.min_num_matches),
      "minimum inlier matches for a pair to count");
  try {
    po::variables_map vm;
    po::store(po::parse_command_line(argc, argv, desc), vm);
    if (vm.count("help")) {
      std::cout << desc << "\n";
      return 0;
    }
    po::notify(vm);
  } catch (const po::error& e) {
    std::cerr << "tmr_graph_info: error: " << e.what() << " (see --help)\n";
    return 2;
  }
  try {
    const auto start = std::chrono::steady_clock::now();
    const tmr::MatchGraph match_graph =
        tmr::ReadMatchGraph(database_path, options);
    const tmr::ImageGraph similarity = tmr::BuildSimilarityGraph(match_graph);
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start)
            .count();
    std::cout << "database          " << database_path << "\n";
    tmr::PrintGraphSummary(tmr::SummarizeGraph(match_graph, similarity),
                           std::cout);
    std::cout << "read + S in       " << seconds << " s\n";
  } catch (const std::exception& e) {
    std::cerr << "tmr_graph_info: error: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
