// Copyright (c) 2026, the tmr authors. BSD-3-Clause.
// What the cameras of a synthetic scene see, and which detections match.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <vector>

#include "synthetic/scene_layout.h"
#include "tmr/colmap/synthetic_scene.h"

namespace tmr {
namespace synthetic {

struct ImageIntrinsics {
  double focal_px;
  int width;
  int height;
};

struct ImageKeypoints {
  std::vector<Eigen::Vector2d> xy;
  // Scene point of each keypoint, -1 for a keypoint that matches nothing.
  std::vector<int> point;
};

// Projects the scene points into every camera: a point is detected when it
// is in front, inside the image, within range, faces the camera, is not
// hidden by another box, and passes the detection probability. Adds noise
// and unmatched keypoints, then shuffles each image's keypoints.
std::vector<ImageKeypoints> DetectKeypoints(
    const SceneLayout& layout, const std::vector<ScenePoint>& points,
    const std::vector<ImageIntrinsics>& intrinsics,
    const SyntheticSceneOptions& options);

struct KeypointMatch {
  uint32_t keypoint1;
  uint32_t keypoint2;
};

struct ImagePairMatches {
  int image1;  // image1 < image2
  int image2;
  std::vector<KeypointMatch> inliers;
  bool is_false = false;  // a false verified pair (repetitive structure)
};

// The verified pairs: detections of the same point in two images match when
// the viewing directions and distances are close enough (and by chance);
// image retrieval keeps each image's max_pairs_per_image best partners; pairs
// with fewer than min_num_inliers matches are dropped. Then false pairs are
// added between images that share no point. Sorted by (image1, image2).
std::vector<ImagePairMatches> MatchKeypoints(
    const SceneLayout& layout, const std::vector<ScenePoint>& points,
    const std::vector<ImageKeypoints>& keypoints,
    const SyntheticSceneOptions& options);

// A reproducible uniform number in [0, 1) from a seed and three integers.
double HashUniform(uint64_t seed, uint64_t a, uint64_t b, uint64_t c);

}  // namespace synthetic
}  // namespace tmr
