// Copyright (c) 2026, the tmr authors. BSD-3-Clause.
// The option rows of the synthetic scene generator (tmr/util/option_table.h)
// and their Check.
#include <algorithm>
#include <numeric>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "tmr/colmap/synthetic_scene.h"

namespace tmr {

namespace {

// "40,90,200" as numbers >= 1; empty for anything else.
std::vector<int> ParseCounts(const std::string& text) {
  std::vector<int> counts;
  std::stringstream in(text);
  for (std::string item; std::getline(in, item, ',');) {
    size_t end = 0;
    int value = 0;
    try {
      value = std::stoi(item, &end);
    } catch (const std::exception&) {
      return {};
    }
    if (end != item.size() || value < 1) return {};
    counts.push_back(value);
  }
  return counts;
}

// The rows of the scene's layout: its family and each family's shape.
void AddLayoutRows(SyntheticSceneOptions* o, OptionTable* t) {
  t->Add("family", &o->family, "places, plazas, street or city");
  t->Add("seed", &o->seed, "random seed");
  t->Add("num_places", &o->num_places, "places, plazas: linked dense places")
      .AtLeast(1);
  t->Add("cameras_per_place", &o->cameras_per_place,
         "places, plazas: ring cameras per place")
      .AtLeast(3);
  t->Add("num_unlinked_places", &o->num_unlinked_places,
         "places: places without link")
      .AtLeast(0);
  t->Add("link_spacing", &o->link_spacing,
         "places: metres between link cameras (0: no link)")
      .AtLeast(0);
  t->Add("place_distance", &o->place_distance, "places: metres between places")
      .AtLeast(60);
  t->Add("place_cameras", &o->place_cameras,
         "places: cameras of each linked place, e.g. 40,90,200 (empty: "
         "num_places x cameras_per_place)");
  t->Add("place_rows", &o->place_rows,
         "places: lengths of the unlinked rows the linked places form, e.g. "
         "3,2 (empty: one row)");
  t->Add("vary_link_lengths", &o->vary_link_lengths,
         "places: links of 1, 1.5 and 2 x place_distance in turn");
  // A plaza's building is 20 m wide; the rings must clear it.
  t->Add("plaza_distance", &o->plaza_distance,
         "plazas: metres between neighbouring plazas")
      .AtLeast(25);
  t->Add("plaza_radius", &o->plaza_radius,
         "plazas: radius of each plaza's camera ring")
      .AtLeast(15);
  t->Add("street_length", &o->street_length, "street: length in metres")
      .Above(0);
  t->Add("street_gap", &o->street_gap, "street: none, removed or thinned");
  t->Add("gap_begin", &o->gap_begin, "street: gap start (fraction of length)")
      .AtLeast(0)
      .AtMost(1);
  t->Add("gap_end", &o->gap_end, "street: gap end (fraction of length)")
      .AtLeast(0)
      .AtMost(1);
  t->Add("gap_thinning", &o->gap_thinning,
         "street: camera spacing factor in a thinned gap")
      .AtLeast(1);
  t->Add("city_blocks_x", &o->city_blocks_x, "city: blocks along x").AtLeast(1);
  t->Add("city_blocks_y", &o->city_blocks_y, "city: blocks along y").AtLeast(1);
  t->Add("camera_spacing", &o->camera_spacing,
         "metres between cameras on streets")
      .Above(0);
}

// The rows of the photos and their observations: cameras, points,
// detection, matching and verification.
void AddObservationRows(SyntheticSceneOptions* o, OptionTable* t) {
  t->Add("image_width", &o->image_width, "image width (pixels)").AtLeast(16);
  t->Add("image_height", &o->image_height, "image height (pixels)").AtLeast(16);
  t->Add("min_focal_px", &o->min_focal_px, "smallest true focal length")
      .Above(0);
  t->Add("max_focal_px", &o->max_focal_px, "largest true focal length")
      .Above(0);
  t->Add("focal_prior_error", &o->focal_prior_error,
         "relative error of the prior focal")
      .AtLeast(0)
      .AtMost(0.5);
  t->Add("point_density", &o->point_density,
         "3D points per square metre of facade")
      .Above(0);
  t->Add("facade_relief", &o->facade_relief,
         "metres points stand off their facade plane (+-)")
      .AtLeast(0);
  t->Add("max_range", &o->max_range, "metres a point can be seen from")
      .Above(0);
  t->Add("max_view_angle_deg", &o->max_view_angle_deg,
         "largest angle between a point's normal and the ray to a camera")
      .Above(0)
      .AtMost(90);
  t->Add("detection_probability", &o->detection_probability,
         "chance a visible point is detected")
      .Above(0)
      .AtMost(1);
  t->Add("keypoint_noise_px", &o->keypoint_noise_px, "keypoint noise (pixels)")
      .AtLeast(0);
  t->Add("unmatched_keypoint_ratio", &o->unmatched_keypoint_ratio,
         "extra keypoints per detection")
      .AtLeast(0);
  t->Add("max_match_angle_deg", &o->max_match_angle_deg,
         "largest viewpoint change (deg) of a match")
      .Above(0)
      .AtMost(180);
  t->Add("match_angle_falloff_deg", &o->match_angle_falloff_deg,
         "viewpoint change (deg) at which matching falls off")
      .Above(0);
  t->Add("max_scale_ratio", &o->max_scale_ratio,
         "largest distance ratio of a match")
      .AtLeast(1);
  t->Add("match_probability", &o->match_probability,
         "chance two detections match")
      .Above(0)
      .AtMost(1);
  t->Add("max_pairs_per_image", &o->max_pairs_per_image,
         "retrieval: partners per image (0: all)")
      .AtLeast(0);
  t->Add("min_num_inliers", &o->min_num_inliers,
         "inlier matches of a verified pair")
      .AtLeast(1);
  t->Add("outlier_match_ratio", &o->outlier_match_ratio,
         "raw-match outliers per inlier")
      .AtLeast(0);
  t->Add("false_pairs_per_100_images", &o->false_pairs_per_100_images,
         "false verified pairs")
      .AtLeast(0);
  t->Add("num_threads", &o->num_threads,
         "threads of the two-view estimation (-1: one per core)")
      .AtLeast(-1);
}

}  // namespace

std::vector<int> SyntheticSceneOptions::PlaceCameras() const {
  if (place_cameras.empty())
    return std::vector<int>(std::max(num_places, 0), cameras_per_place);
  return ParseCounts(place_cameras);
}

std::vector<int> SyntheticSceneOptions::PlaceRows() const {
  if (place_rows.empty()) return {static_cast<int>(PlaceCameras().size())};
  return ParseCounts(place_rows);
}

void SyntheticSceneOptions::AddTo(OptionTable* t) {
  AddLayoutRows(this, t);
  AddObservationRows(this, t);
}

bool SyntheticSceneOptions::Check(std::string* error) const {
  auto fail = [&](const std::string& message) {
    if (error) *error = message;
    return false;
  };
  if (family != "places" && family != "plazas" && family != "street" &&
      family != "city") {
    return fail("family must be places, plazas, street or city, not '" +
                family + "'");
  }
  if (street_gap != "none" && street_gap != "removed" &&
      street_gap != "thinned") {
    return fail("street_gap must be none, removed or thinned");
  }
  if (!CheckOptionRows(*this, error)) return false;
  const std::vector<int> cameras = PlaceCameras();
  if (cameras.empty() ||
      std::any_of(cameras.begin(), cameras.end(), [](int n) { return n < 3; }))
    return fail("place_cameras must list numbers >= 3, e.g. 40,90,200");
  const std::vector<int> rows = PlaceRows();
  if (rows.empty() ||
      std::accumulate(rows.begin(), rows.end(), size_t{0}) != cameras.size())
    return fail("place_rows must list row lengths that add up to the places");
  if (gap_begin >= gap_end) return fail("gap_begin must be below gap_end");
  if (max_focal_px < min_focal_px)
    return fail("max_focal_px must be at least min_focal_px");
  return true;
}

}  // namespace tmr
