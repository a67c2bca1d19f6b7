// Copyright (c) 2026, the tmr authors. BSD-3-Clause.
// tmr_synth --database_path DB [--model_path DIR]: writes a synthetic scene
// as a COLMAP database (through COLMAP's Database class) plus ground truth.
#include <boost/program_options.hpp>

#include <iostream>

#include "tmr/colmap/synthetic_scene.h"

namespace po = boost::program_options;

int main(int argc, char** argv) {
  std::string database_path, model_path;
  tmr::SyntheticSceneOptions options;
  po::options_description desc(
      "tmr_synth: synthetic scene as a COLMAP database plus ground truth");
  desc.add_options()("help,h", "print this help")(
      "database_path", po::value(&database_path)->required(),
      "database to write (must not exist)")(
      "model_path", po::value(&model_path),
      "folder for the ground-truth model (COLMAP binary)")(
      "num_images",
      po::value(&options.num_images)->default_value(options.num_images),
      "number of images")(
      "num_cameras",
      po::value(&options.num_cameras)->default_value(options.num_cameras),
      "number of distinct cameras")(
      "num_points3D",
      po::value(&options.num_points3D)->default_value(options.num_points3D),
      "number of 3D points")(
      "num_unmatched_keypoints",
      po::value(&options.num_unmatched_keypoints)
          ->default_value(options.num_unmatched_keypoints),
      "keypoints per image that match nothing")(
      "keypoint_noise_px",
      po::value(&options.keypoint_noise_px)
          ->default_value(options.keypoint_noise_px),
      "keypoint noise (pixels)")(
      "seed", po::value(&options.seed)->default_value(options.seed),
      "random seed");
  try {
    po::variables_map vm;
    po::store(po::parse_command_line(argc, argv, desc), vm);
    if (vm.count("help")) {
      std::cout << desc << "\n";
      return 0;
    }
    po::notify(vm);
  } catch (const po::error& e) {
    std::cerr << "tmr_synth: error: " << e.what() << " (see --help)\n";
    return 2;
  }
  std::string error;
  try {
    if (!tmr::WriteSyntheticScene(options, database_path, model_path, &error)) {
      std::cerr << "tmr_synth: error: " << error << "\n";
      return 1;
    }
  } catch (const std::exception& e) {
    std::cerr << "tmr_synth: error: " << e.what() << "\n";
    return 1;
  }
  std::cout << "wrote " << database_path << " (" << options.num_images
            << " images)";
  if (!model_path.empty()) std::cout << " and ground truth " << model_path;
  std::cout << "\n";
  return 0;
}
