// Copyright (c) 2026, the tmr authors. BSD-3-Clause.
// tmr_mapper --database_path DB --image_path IMAGES --output_path OUT:
// the drop-in replacement for `colmap mapper`, reconstructing on the
// TMR-tree. COLMAP's --Mapper.* options pass through; tmr's are --Tmr.*.
#include <boost/program_options.hpp>

#include <filesystem>
#include <iomanip>
#include <iostream>

#include "mapper_options.h"
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
  tmr::AddTmrMapperOptions(&desc, &o);
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
  const auto progress = tmr::TimedProgressLines();
  tmr::TmrMapperReport report;
  try {
    // project.ini: the effective options, as COLMAP writes them.
    std::error_code ec;
    fs::create_directories(o.output_path, ec);
    if (ec) {
      std::cerr << "tmr_mapper: error: cannot create output folder '"
                << o.output_path << "': " << ec.message() << "\n";
      return 1;
    }
    tmr::WriteFileAtomically((fs::path(o.output_path) / "project.ini").string(),
                             tmr::ProjectIni(desc, vm));
    if (!tmr::RunTmrMapper(o, &report, &error, progress)) {
      std::cerr << "tmr_mapper: error: " << error << "\n";
      return 1;
    }
    tmr::DrawMapperPartitionPicture(o);
  } catch (const std::exception& e) {
    std::cerr << "tmr_mapper: error: " << e.what() << "\n";
    return 1;
  }
  std::cout << "tmr_mapper: " << report.num_images << " images, "
            << report.model_sizes.size() << " models (registered:";
  for (const int size : report.model_sizes) std::cout << " " << size;
  std::cout << ") in " << std::fixed << std::setprecision(1)
            << report.total_seconds << " s\n";
  return 0;
}
