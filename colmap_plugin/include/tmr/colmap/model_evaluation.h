// Copyright (c) 2026, the tmr authors. BSD-3-Clause.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

#include "tmr/colmap/match_consistency_options.h"

namespace tmr {

struct ModelEvaluationOptions {
  // RANSAC inlier threshold of the sim3 alignment on camera centres, as a
  // share of the scene scale (RMS distance of the common reference cameras
  // from their centroid).
  double inlier_threshold = 0.01;
  // An image is displaced when its position error after the alignment is
  // above this share of the scene scale.
  double displaced_threshold = 0.05;
  // A wrong merge is flagged when at least this many displaced images form a
  // rigid part of their own (a second sim3 fits them).
  int min_wrong_merge_images = 5;
  // Seed of the RANSAC sampling.
  unsigned seed = 0;
  // When set: the COLMAP database the model was reconstructed from (opened
  // read-only); its verified matches between registered images are checked
  // against the model's poses, which needs no ground truth.
  std::string database_path;
  // How that check tests and judges the matches.
  MatchConsistencyOptions match_consistency;

  bool Check(std::string* error = nullptr) const;
};

struct ErrorStatistics {
  double median = 0.0;
  double p90 = 0.0;
  double max = 0.0;
};

// Scores of one model against a reference (ground truth or another model).
struct ModelEvaluation {
  std::string model_path;
  int num_registered_images = 0;
  int num_points3D = 0;
  double mean_reprojection_error_px = 0.0;
  double mean_track_length = 0.0;
  // Points by track length: index k counts tracks of length k (the last bin
  // holds all longer ones); indices 0 and 1 stay 0.
  std::vector<int> track_length_histogram;

  int num_reference_images = 0;  // registered in the reference
  int num_common_images = 0;     // registered in both, matched by name
  bool aligned = false;          // false: fewer than 3 common images or no fit
  int num_alignment_inliers = 0;
  double scene_scale = 0.0;  // in reference units
  // Orientation errors after the rotation that best maps the model's
  // orientations onto the reference's (a robust mean over the images).
  ErrorStatistics rotation_error_deg;
  // The same errors after the sim3 fitted to the camera centres, as
  // COLMAP's ComputeImageAlignmentError gives them. Its rotation is only as
  // good as the centres constrain it, which on small or flat camera layouts
  // adds more error than it measures.
  ErrorStatistics centre_aligned_rotation_error_deg;
  ErrorStatistics position_error;  // share of the scene scale

  bool wrong_merge = false;
  int num_displaced_images = 0;
  // Their names, most displaced first.
  std::vector<std::string> displaced_image_names;
  // Median distance of the displaced rigid part from its true place, as a
  // share of the scene scale, and its rotation against the main part.
  double displacement = 0.0;
  double displacement_rotation_deg = 0.0;
  // Camera centres of the model's registered images in the reference's
  // frame (empty when not aligned).
  std::vector<std::array<double, 3>> aligned_centres;
  // Names of the model's registered images.
  std::vector<std::string> image_names;
  // With options.database_path: the model against the database's verified
  // matches (tmr/colmap/match_consistency_options.h), tested and judged with
  // options.match_consistency.
  std::optional<MatchConsistency> match_consistency;
  bool match_consistent = false;  // match_consistency passes the options
};

// Reads the reference and the model (COLMAP models, binary or text) and
// scores the model; with an empty reference_path only the model's own
// statistics (images, points, reprojection error, tracks). Throws
// std::runtime_error for unreadable models or databases.
ModelEvaluation EvaluateModel(const std::string& reference_path,
                              const std::string& model_path,
                              const ModelEvaluationOptions& options);

// Camera centres of the registered images of a COLMAP model. Throws
// std::runtime_error for an unreadable model.
std::vector<std::array<double, 3>> ReadCameraCentres(
    const std::string& model_path);

void PrintEvaluationTable(const std::vector<ModelEvaluation>& evaluations,
                          std::ostream& out);
// Writes {"reference": ..., "models": [...], "images_in_several_models": N}
// where N counts the image names registered in more than one of the models.
void WriteEvaluationJson(const std::vector<ModelEvaluation>& evaluations,
                         const std::string& reference_path, std::ostream& out);

}  // namespace tmr
