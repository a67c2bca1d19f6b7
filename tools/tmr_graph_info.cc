// Copyright (c) 2026, the tmr authors. BSD-3-Clause.
// tmr_graph_info --database_path DB: reads the verified match graph of a
// COLMAP database (read-only) and prints the similarity graph S of Eq. 1.
#include <boost/program_options.hpp>

#include <chrono>
#include <fstream>
#include <iostream>

#include "tmr/io/database_reader.h"
#include "tmr/scene/graph_summary.h"
#include "tmr/scene/image_graph.h"

#include "command_line.h"

namespace po = boost::program_options;

int main(int argc, char** argv) {
  std::string database_path, histogram_csv;
  tmr::MatchGraphOptions options;
  po::options_description desc(
      "tmr_graph_info: summary of the match graph of a COLMAP database");
  desc.add_options()("help,h", "print this help")(
      "database_path", po::value(&database_path)->required(),
      "COLMAP database.db (opened read-only)")(
      "min_num_matches",
      po::value(&options.min_num_matches)
          ->default_value(options.min_num_matches),
      "minimum inlier matches for a pair to count")(
      "histogram_csv", po::value(&histogram_csv),
      "write the histogram of s_ij (50 bins over [0, 1]) as CSV");
  po::variables_map vm;
  if (const auto exit_code =
          tmr::ParseCommandLine("tmr_graph_info", argc, argv, desc, &vm)) {
    return *exit_code;
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
    if (!histogram_csv.empty()) {
      const tmr::GraphSummary fine = tmr::SummarizeGraph(
          match_graph, similarity, /*num_histogram_bins=*/50);
      std::ofstream out(histogram_csv);
      out << "bin_low,bin_high,count,fraction\n";
      for (int b = 0; b < 50; ++b) {
        const int count = fine.similarity_histogram[b];
        out << b / 50.0 << "," << (b + 1) / 50.0 << "," << count << ","
            << (fine.num_pairs ? static_cast<double>(count) / fine.num_pairs
                               : 0.0)
            << "\n";
      }
      if (!out)
        throw std::runtime_error("cannot write '" + histogram_csv + "'");
    }
  } catch (const std::exception& e) {
    std::cerr << "tmr_graph_info: error: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
