// Copyright (c) 2026, the tmr authors. BSD-3-Clause.
// The options and the result of checking a model against the verified
// matches of its database (CheckMatchConsistency in colmap_plugin; tmr_eval
// --database_path).
#pragma once

#include <cstdint>
#include <string>

namespace tmr {

struct MatchConsistencyOptions {
  // A verified match is inconsistent with the model when, triangulated from
  // the model's poses and cameras, it reprojects farther than this (pixels)
  // in one of its images. COLMAP verifies matches at 4 px.
  double max_reprojection_error = 4.0;
  // Matches whose rays meet at less than this angle (degrees) at the
  // triangulated point are not tested: their depth is ill-determined
  // (forward motion, distant points), and on real photos such matches
  // contradict correct models (docs/benchmarks.md, "The kernel check on
  // real photos"). COLMAP's default filter_min_tri_angle.
  double min_triangulation_angle_deg = 1.5;
  // Only matches that a third photo confirms are tested: a keypoint of
  // another photo is matched to both of their keypoints (a triangle of
  // verified matches). A matcher's verification keeps false matches that
  // fit a pair's estimated geometry (COLMAP: within 4 px of an epipolar
  // line or a homography), no pose can place them, and a correct model
  // contradicts them as much as a wrong one; a false match between two
  // photos is rarely repeated with a third (docs/mapper.md, "The kernel
  // check"). A wrong model contradicts matches of tracks seen from three or
  // more photos as well. false: every match is tested.
  bool require_third_view = true;
  // A model is inconsistent when more than this share of the verified
  // matches between its registered images is inconsistent (calibrated in
  // docs/mapper.md, "The kernel check": correct models 0.00-0.20%, wrong
  // ones 0.45% and more) ...
  double max_inconsistent_share = 0.003;
  // ... or when more than this many image pairs are: pairs with at least
  // min_pair_matches tested matches of which more than half are
  // inconsistent.
  int max_inconsistent_pairs = 5;
  int min_pair_matches = 15;

  bool Check(std::string* error = nullptr) const;
};

// Verified matches of a model's registered image pairs against its poses.
struct MatchConsistency {
  int64_t num_matches = 0;          // inlier matches of registered pairs
  int64_t num_in_common_track = 0;  // both keypoints in the same 3D point
  int64_t num_unconfirmed = 0;      // the others, no third photo confirms them
  int64_t num_low_angle = 0;       // the others, in front at too small an angle
  int64_t num_tested = 0;          // the others, in front at a sufficient angle
  int64_t num_inconsistent = 0;    // of those, reprojecting too far
  int num_pairs = 0;               // registered pairs with matches
  int num_inconsistent_pairs = 0;  // see MatchConsistencyOptions

  double InconsistentShare() const {
    return num_matches > 0 ? static_cast<double>(num_inconsistent) /
                                 static_cast<double>(num_matches)
                           : 0.0;
  }
  bool IsConsistent(const MatchConsistencyOptions& options) const {
    return InconsistentShare() <= options.max_inconsistent_share &&
           num_inconsistent_pairs <= options.max_inconsistent_pairs;
  }
};

}  // namespace tmr
