// Copyright (c) 2026, the tmr authors. BSD-3-Clause.
// tmr_synth --database_path DB [--model_path DIR] [--family
// places|plazas|street|city] writes a synthetic scene as a COLMAP database
// (through COLMAP's Database class) plus its ground-truth model. See
// docs/synthetic_scenes.md.
#include <boost/program_options.hpp>

#include <chrono>
#include <iostream>

#include "tmr/colmap/synthetic_scene.h"

#include "command_line.h"

namespace po = boost::program_options;

int main(int argc, char** argv) {
  std::string database_path, model_path;
  tmr::SyntheticSceneOptions o;
  po::options_description desc(
      "tmr_synth: synthetic scene as a COLMAP database plus ground truth");
  desc.add_options()("help,h", "print this help")(
      "database_path", po::value(&database_path)->required(),
      "database to write (must not exist)")(
      "model_path", po::value(&model_path),
      "folder for the ground-truth model (COLMAP binary)");
  tmr::AddOptionsOf(&desc, &o);
  po::variables_map vm;
  if (const auto exit_code =
          tmr::ParseCommandLine("tmr_synth", argc, argv, desc, &vm)) {
    return *exit_code;
  }
  const auto start = std::chrono::steady_clock::now();
  std::string error;
  tmr::SyntheticSceneSummary summary;
  try {
    if (!tmr::WriteSyntheticScene(o, database_path, model_path, &summary,
                                  &error)) {
      std::cerr << "tmr_synth: error: " << error << "\n";
      return 1;
    }
  } catch (const std::exception& e) {
    std::cerr << "tmr_synth: error: " << e.what() << "\n";
    return 1;
  }
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start)
          .count();
  std::cout << "wrote " << database_path << ": " << summary.num_images
            << " images, " << summary.num_verified_pairs << " verified pairs (+"
            << summary.num_false_pairs << " false), "
            << summary.mean_keypoints_per_image << " keypoints/image";
  if (!model_path.empty()) {
    std::cout << "; ground truth " << model_path << ": " << summary.num_points3D
              << " points, mean track length " << summary.mean_track_length;
  }
  std::cout << " (" << seconds << " s)\n";
  return 0;
}
