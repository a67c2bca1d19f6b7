// Copyright (c) 2026, the tmr authors. BSD-3-Clause.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "tmr/util/option_table.h"

namespace tmr {

// Options of the synthetic scene generator (tools/tmr_synth). A scene is a
// set of textured boxes (buildings, walls) and cameras that look at them; it
// is written as a COLMAP database (keypoints, raw matches, verified two-view
// geometries) plus the ground-truth model. See docs/synthetic_scenes.md.
//
// Families:
//   places  num_places dense places (a building with a ring of cameras) on a
//           line, consecutive ones joined by a corridor of cameras every
//           link_spacing metres (0: no link), plus num_unlinked_places far
//           away (the paper's Fig. 1: A and B weakly linked, C alone).
//   plazas  num_places plazas (a building with a ring of cameras_per_place
//           cameras of radius plaza_radius) on a grid, plaza_distance apart:
//           the rings overlap heavily and there are no link cameras, so the
//           scene is one well-connected place whose photos each see several
//           buildings (a town centre photographed by many visitors).
//   street  a straight street of cameras every camera_spacing metres with
//           facades on both sides; the stretch [gap_begin, gap_end] (fraction
//           of the length) is kept, removed (no link) or thinned (weak link),
//           as in the paper's Sec. 6.2.
//   city    a grid of blocks with cameras along every street; with a small
//           camera_spacing it is a well-connected scene that stock COLMAP
//           builds as one model, with many blocks a large city for scaling.
struct SyntheticSceneOptions {
  // Scene family: "places", "plazas", "street" or "city".
  std::string family = "places";
  // Seed of every random choice; the same options give the same database.
  uint64_t seed = 0;

  // --- places ---
  // Number of linked dense places and cameras on the ring of each.
  int num_places = 2;
  int cameras_per_place = 60;
  // Places with no link to anything.
  int num_unlinked_places = 1;
  // Metres between the cameras of a link corridor; 0 removes the links.
  double link_spacing = 3.0;
  // Distance between the centres of consecutive places (metres).
  double place_distance = 120.0;
  // Cameras of each linked place, e.g. "40,90,200,60" (places of several
  // sizes); empty: num_places places of cameras_per_place.
  std::string place_cameras;
  // The linked places form rows of these lengths, e.g. "3,2": places 0-2
  // linked along one row, places 3-4 along another, out of every camera's
  // range of the first; empty: one row.
  std::string place_rows;
  // Consecutive links of a row are 1, 1.5 and 2 times place_distance long
  // in turn (streets of several lengths); false: all place_distance.
  bool vary_link_lengths = false;

  // --- plazas (num_places and cameras_per_place as above) ---
  // Distance between the centres of neighbouring plazas on the grid and the
  // radius of each plaza's camera ring (metres): rings 120 m across, 45 m
  // apart.
  double plaza_distance = 45.0;
  double plaza_radius = 60.0;

  // --- street ---
  // Length of the street (metres).
  double street_length = 400.0;
  // "none", "removed" or "thinned".
  std::string street_gap = "none";
  double gap_begin = 0.45;
  double gap_end = 0.6;
  // In a thinned gap the cameras are this many times farther apart.
  double gap_thinning = 6.0;

  // --- city ---
  // Blocks along x and y.
  int city_blocks_x = 3;
  int city_blocks_y = 3;

  // --- shared: cameras ---
  // Metres between consecutive cameras along streets and corridors.
  double camera_spacing = 2.0;
  int image_width = 1024;
  int image_height = 768;
  // True focal lengths are drawn uniformly from [min, max] per image (every
  // image has its own camera, as photos from many devices do).
  double min_focal_px = 850.0;
  double max_focal_px = 1250.0;
  // The database's prior focal length is the true one times
  // (1 + N(0, focal_prior_error)).
  double focal_prior_error = 0.03;

  // --- shared: observations and matching ---
  // Texture: 3D points per square metre of facade.
  double point_density = 10.0;
  // Facade relief: points stand up to this far in front of or behind their
  // facade plane (windows, balconies, signs). Perfectly planar facades make
  // focal length and depth hard to tell apart in bundle adjustment, which
  // real facades rarely do.
  double facade_relief = 0.4;
  // A point is seen only within this distance and when the angle between
  // its surface normal and the ray to the camera is below max_view_angle.
  double max_range = 60.0;
  double max_view_angle_deg = 70.0;
  // A visible point is detected as a keypoint with this probability.
  double detection_probability = 0.6;
  // Keypoint noise in pixels (standard deviation).
  double keypoint_noise_px = 0.7;
  // Extra keypoints that match nothing, as a share of the detected ones.
  double unmatched_keypoint_ratio = 0.5;
  // Two detections of a point match only if the viewing directions differ by
  // less than max_match_angle and the distances by less than
  // max_scale_ratio, and then with probability
  // match_probability * exp(-angle^2 / (2 * match_angle_falloff^2)), as
  // descriptors tolerate a viewpoint change less the larger it is.
  double max_match_angle_deg = 60.0;
  double match_angle_falloff_deg = 25.0;
  double max_scale_ratio = 3.0;
  double match_probability = 0.9;
  // Image retrieval: each image is matched with the images that share the
  // most points with it, at most this many (0: every overlapping pair).
  int max_pairs_per_image = 40;
  // Verified pairs need at least this many inlier matches.
  int min_num_inliers = 15;
  // Raw matches of a pair add this share of random outliers to the inliers.
  double outlier_match_ratio = 0.3;
  // Number of false verified pairs (repetitive structure) per 100 images,
  // each between two images that share no point, with 15 to 40 inliers.
  double false_pairs_per_100_images = 1.0;

  // Threads that estimate the pairs' two-view geometries (-1: one per
  // core); the database does not depend on it.
  int num_threads = -1;

  // Lists the options as rows (tmr/util/option_table.h): tmr_synth's
  // command line reads them.
  void AddTo(OptionTable* table);
  // Returns false (and fills `error`) for impossible values.
  bool Check(std::string* error = nullptr) const;
  // Cameras of each linked place (place_cameras, else num_places times
  // cameras_per_place) and the lengths of the rows they form (place_rows,
  // else one row); empty when the text does not parse.
  std::vector<int> PlaceCameras() const;
  std::vector<int> PlaceRows() const;
};

// Figures of a written scene.
struct SyntheticSceneSummary {
  int num_images = 0;
  int num_points3D = 0;
  int num_verified_pairs = 0;
  int num_false_pairs = 0;
  double mean_keypoints_per_image = 0.0;
  double mean_track_length = 0.0;
};

// Writes `database_path` (must not exist yet) through COLMAP's Database class
// and the ground truth in COLMAP binary format into `model_path` (created if
// missing; empty: no model). Image names are "<part>/<number>.jpg", where the
// part is "place0", "link0-1", "street", "city", ... Returns false with a
// reason in `error` on failure.
bool WriteSyntheticScene(const SyntheticSceneOptions& options,
                         const std::string& database_path,
                         const std::string& model_path,
                         SyntheticSceneSummary* summary, std::string* error);

}  // namespace tmr
