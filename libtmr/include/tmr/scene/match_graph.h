// Copyright (c) 2026, the tmr authors. BSD-3-Clause.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace tmr {

// One image of the match graph. Plain data, no COLMAP types.
struct MatchGraphImage {
  // COLMAP's image_id (1-based in COLMAP databases).
  uint32_t image_id = 0;
  // Image name relative to the image folder, as stored in the database.
  std::string name;
  uint32_t camera_id = 0;
  // Number of keypoints stored for the image (0 if none).
  int num_keypoints = 0;
  // n_i of Eq. 1: keypoints of this image that take part in at least one
  // inlier match of a counted pair (see MatchGraphOptions).
  int num_matched_keypoints = 0;
};

// One verified image pair. image1 < image2 are indices into
// MatchGraph::images, not database ids.
struct MatchGraphPair {
  int image1 = 0;
  int image2 = 0;
  // n_ij of Eq. 1: number of inlier matches of the two-view geometry.
  int num_inliers = 0;
  // COLMAP's TwoViewGeometry::ConfigurationType of the pair.
  int config = 0;
};

// The verified match graph of an image collection: vertices are images,
// edges are image pairs with a verified two-view geometry. Images are sorted
// by image_id, pairs by (image1, image2).
struct MatchGraph {
  std::vector<MatchGraphImage> images;
  std::vector<MatchGraphPair> pairs;

  int NumImages() const { return static_cast<int>(images.size()); }
  int NumPairs() const { return static_cast<int>(pairs.size()); }
  // Index into `images` of a database image_id, or -1 if it is not present.
  int FindImageIndex(uint32_t image_id) const;
};

}  // namespace tmr
