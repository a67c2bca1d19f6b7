// Copyright (c) 2026, the tmr authors. BSD-3-Clause.
// tmr_synth --database_path DB [--model_path DIR] [--family
// places|plazas|street|city] writes a synthetic scene as a COLMAP database
// (through COLMAP's Database class) plus its ground-truth model. See
// docs/synthetic_scenes.md.
#include <boost/program_options.hpp>

#include <chrono>
#include <iostream>

#include "tmr/colmap/synthetic_scene.h"

#include "tmr_options.h"

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
  tmr::AddOption(&desc, "family", &o.family, "places, plazas, street or city");
  tmr::AddOption(&desc, "seed", &o.seed, "random seed");
  tmr::AddOption(&desc, "num_places", &o.num_places,
                 "places, plazas: linked dense places");
  tmr::AddOption(&desc, "cameras_per_place", &o.cameras_per_place,
                 "places, plazas: ring cameras per place");
  tmr::AddOption(&desc, "num_unlinked_places", &o.num_unlinked_places,
                 "places: places without link");
  tmr::AddOption(&desc, "link_spacing", &o.link_spacing,
                 "places: metres between link cameras (0: no link)");
  tmr::AddOption(&desc, "place_distance", &o.place_distance,
                 "places: metres between places");
  tmr::AddOption(&desc, "place_cameras", &o.place_cameras,
                 "places: cameras of each linked place, e.g. 40,90,200 "
                 "(empty: num_places x cameras_per_place)");
  tmr::AddOption(&desc, "place_rows", &o.place_rows,
                 "places: lengths of the unlinked rows the linked places "
                 "form, e.g. 3,2 (empty: one row)");
  tmr::AddOption(&desc, "vary_link_lengths", &o.vary_link_lengths,
                 "places: links of 1, 1.5 and 2 x place_distance in turn");
  tmr::AddOption(&desc, "plaza_distance", &o.plaza_distance,
                 "plazas: metres between neighbouring plazas");
  tmr::AddOption(&desc, "plaza_radius", &o.plaza_radius,
                 "plazas: radius of each plaza's camera ring");
  tmr::AddOption(&desc, "street_length", &o.street_length,
                 "street: length in metres");
  tmr::AddOption(&desc, "street_gap", &o.street_gap,
                 "street: none, removed or thinned");
  tmr::AddOption(&desc, "gap_begin", &o.gap_begin,
                 "street: gap start (fraction of length)");
  tmr::AddOption(&desc, "gap_end", &o.gap_end,
                 "street: gap end (fraction of length)");
  tmr::AddOption(&desc, "gap_thinning", &o.gap_thinning,
                 "street: camera spacing factor in a thinned gap");
  tmr::AddOption(&desc, "city_blocks_x", &o.city_blocks_x,
                 "city: blocks along x");
  tmr::AddOption(&desc, "city_blocks_y", &o.city_blocks_y,
                 "city: blocks along y");
  tmr::AddOption(&desc, "camera_spacing", &o.camera_spacing,
                 "metres between cameras on streets");
  tmr::AddOption(&desc, "min_focal_px", &o.min_focal_px,
                 "smallest true focal length");
  tmr::AddOption(&desc, "max_focal_px", &o.max_focal_px,
                 "largest true focal length");
  tmr::AddOption(&desc, "focal_prior_error", &o.focal_prior_error,
                 "relative error of the prior focal");
  tmr::AddOption(&desc, "point_density", &o.point_density,
                 "3D points per square metre of facade");
  tmr::AddOption(&desc, "facade_relief", &o.facade_relief,
                 "metres points stand off their facade plane (+-)");
  tmr::AddOption(&desc, "max_range", &o.max_range,
                 "metres a point can be seen from");
  tmr::AddOption(&desc, "detection_probability", &o.detection_probability,
                 "chance a visible point is detected");
  tmr::AddOption(&desc, "keypoint_noise_px", &o.keypoint_noise_px,
                 "keypoint noise (pixels)");
  tmr::AddOption(&desc, "unmatched_keypoint_ratio", &o.unmatched_keypoint_ratio,
                 "extra keypoints per detection");
  tmr::AddOption(&desc, "match_probability", &o.match_probability,
                 "chance two detections match");
  tmr::AddOption(&desc, "match_angle_falloff_deg", &o.match_angle_falloff_deg,
                 "viewpoint change (deg) at which matching falls off");
  tmr::AddOption(&desc, "max_pairs_per_image", &o.max_pairs_per_image,
                 "retrieval: partners per image (0: all)");
  tmr::AddOption(&desc, "outlier_match_ratio", &o.outlier_match_ratio,
                 "raw-match outliers per inlier");
  tmr::AddOption(&desc, "false_pairs_per_100_images",
                 &o.false_pairs_per_100_images, "false verified pairs");
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
