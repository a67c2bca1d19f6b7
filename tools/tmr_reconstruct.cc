// Copyright (c) 2026, the tmr authors. BSD-3-Clause.
// tmr_reconstruct IMAGES OUT [options]: from a folder of photos to models.
// COLMAP's feature extraction (CPU SIFT) and matching into OUT/database.db,
// then tmr_mapper into OUT/sparse; OUT/summary.txt sums it up. A rerun
// reuses the features and matches already in OUT/database.db.
#include <boost/program_options.hpp>

#include <filesystem>
#include <iostream>

#include "command_line.h"
#include "progress_lines.h"
#include "report/report_page.h"
#include "tmr/colmap/reconstruct_images.h"
#include "tmr/io/atomic_file.h"

namespace fs = std::filesystem;
namespace po = boost::program_options;

int main(int argc, char** argv) {
  tmr::ReconstructImagesOptions o;
  bool verbose = false;
  po::options_description desc(
      "tmr_reconstruct IMAGES OUT [options]: COLMAP feature extraction and "
      "matching, then tmr_mapper");
  desc.add_options()("help,h", "print this help")(
      "image_path", po::value(&o.image_path)->required(),
      "folder of photos (JPEG, PNG, ...), read-only")(
      "workspace_path", po::value(&o.workspace_path)->required(),
      "output: database.db, sparse/0, 1, ..., summary.txt");
  tmr::AddOption(&desc, "verbose", &verbose, "show COLMAP's own log");
  tmr::AddOptionsOf(&desc, &o);
  po::positional_options_description positional;
  positional.add("image_path", 1).add("workspace_path", 1);
  po::variables_map vm;
  if (const auto exit_code = tmr::ParseCommandLine(
          "tmr_reconstruct", argc, argv, desc, &vm, positional)) {
    return *exit_code;
  }
  std::string error;
  if (!o.Check(&error)) {
    std::cerr << "tmr_reconstruct: error: " << error << "\n";
    return 2;
  }
  tmr::ConfigureColmapLogging(argv[0], verbose);
  tmr::ReconstructImagesReport report;
  try {
    if (!tmr::RunReconstructImages(o, &report, &error,
                                   tmr::TimedProgressLines())) {
      std::cerr << "tmr_reconstruct: error: " << error << "\n";
      return 1;
    }
    const tmr::TmrMapperOptions mapper = o.MapperOptions();
    tmr::WriteFileAtomically(
        (fs::path(mapper.output_path) / "project.ini").string(),
        tmr::ProjectIni(desc, vm));
    tmr::WriteRunPictures(mapper.database_path, mapper.match_graph,
                          mapper.output_path, tmr::TimedProgressLines());
  } catch (const std::exception& e) {
    std::cerr << "tmr_reconstruct: error: " << e.what() << "\n";
    return 1;
  }
  std::cout << tmr::ReconstructImagesSummary(report);
  return 0;
}
