// Copyright (c) 2026, the tmr authors. BSD-3-Clause.
#pragma once

#include <stdexcept>
#include <string>
#include <vector>

#include "tmr/scene/match_graph.h"

namespace tmr {

// Thrown for every problem with the input database. The message names the
// database path and the problem in one line.
class DatabaseError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct MatchGraphOptions {
  // A pair is an edge when its two-view geometry has at least this many
  // inlier matches (COLMAP's --Mapper.min_num_matches default).
  int min_num_matches = 15;

  // COLMAP TwoViewGeometry::ConfigurationType values that count as verified.
  // Default: CALIBRATED (2), UNCALIBRATED (3), PLANAR (4), PANORAMIC (5),
  // PLANAR_OR_PANORAMIC (6), MULTIPLE (8), CALIBRATED_RIG (9, COLMAP 4's
  // rig verification). WATERMARK (7) is left out, as COLMAP's mapper does
  // with ignore_watermarks; UNDEFINED (0) and DEGENERATE (1) never count.
  std::vector<int> verified_configs = {2, 3, 4, 5, 6, 8, 9};

  // Returns false (and fills `error`) for impossible values.
  bool Check(std::string* error = nullptr) const;
};

// Reads the verified match graph from a COLMAP database (schemas of COLMAP
// 3.8 to 4.x; tables that are not needed, such as rigs and frames, are
// ignored). The file is opened read-only and is never modified.
//
// Reads images (id, name, camera), keypoint counts and the two-view
// geometries. The inlier blobs of the counted pairs are streamed once to
// compute n_i, the number of keypoints of each image that take part in at
// least one counted inlier match (Eq. 1 of the paper).
//
// Throws DatabaseError for a missing or non-SQLite file, missing tables or
// columns, and inconsistent data (blob size not rows x cols x 4 bytes, a pair
// naming an unknown image, a match index beyond the image's keypoints).
// Throws std::invalid_argument when options.Check() fails.
MatchGraph ReadMatchGraph(const std::string& database_path,
                          const MatchGraphOptions& options = {});

// The images of a COLMAP database (id, name, camera; keypoint counts left
// 0), sorted by id, as ReadMatchGraph reads them; for a stage that needs
// the names and ids but not the matches. Throws DatabaseError.
std::vector<MatchGraphImage> ReadDatabaseImages(
    const std::string& database_path);

}  // namespace tmr
