// Copyright (c) 2026, the tmr authors. BSD-3-Clause.
//
// Bundle adjustment of a merged model whose whole problem would take more
// memory than one wants to spend: the model is adjusted on its longest
// tracks, then block by block (AdjustByBlocks).
#pragma once

#include <colmap/estimators/bundle_adjustment.h>
#include <colmap/scene/reconstruction.h>

#include <string>
#include <unordered_map>
#include <unordered_set>
#include <vector>

namespace tmr {

// Triangulates the point again from its track with the model's poses
// (COLMAP's multi-view DLT on normalized coordinates) where that fits its
// observations better than its current position.
void RetriangulateIfBetter(colmap::Reconstruction* model,
                           colmap::point3D_t point_id);

// Gives each registered image of `model` that `cam_from_world` holds that
// pose; each of `point_ids` first moves rigidly with the first image that
// observes it (from its pose in `model` to its new one), then is
// triangulated again where that fits better (RetriangulateIfBetter), on
// num_threads: a model's points after an adjustment of its poses on a part
// of its points.
void MoveToPoses(
    const std::unordered_map<colmap::image_t, colmap::Rigid3d>& cam_from_world,
    const std::vector<colmap::point3D_t>& point_ids,
    colmap::Reconstruction* model, int num_threads = 1);

// Cuts the registered images of `model` into blocks of at most max_images
// that are each grown breadth-first over shared 3D points (region growing
// on the co-visibility graph), seeds taken in the breadth-first order of the
// whole model from its smallest image id. Every registered image is in
// exactly one block, and each block is connected through shared points.
std::vector<std::vector<colmap::image_t>> CovisibleImageBlocks(
    const colmap::Reconstruction& model, size_t max_images);

// One block's adjustment, as COLMAP's local bundle adjustment
// (IncrementalMapper::AdjustLocalBundle) with the block for its window: the
// block's poses, cameras and points are free; a point that images outside
// the block also observe keeps those observations, with their poses held.
// A block that no outside image constrains gets COLMAP's global gauge
// (first pose and one coordinate of the second position held). The
// intrinsics of `held_cameras` stay as they are.
struct BlockAdjustment {
  int num_iterations = 0;
  bool converged = false;
  double initial_cost = 0;
  double final_cost = 0;
};
BlockAdjustment AdjustBlock(
    const std::vector<colmap::image_t>& block,
    const colmap::BundleAdjustmentOptions& options,
    colmap::Reconstruction* model,
    const std::unordered_set<colmap::camera_t>& held_cameras = {});

// The adjustments of several blocks added up.
struct BlockAdjustmentTotals {
  int num_converged = 0;
  int num_iterations = 0;
  double initial_cost = 0;
  double final_cost = 0;
  void Add(const BlockAdjustment& block);
  // "N converged, I iterations, cost A -> B".
  std::string Describe() const;
};

// Global bundle adjustment of every pose and camera of the model with
// COLMAP's residuals, loss and gauge, but a direct sparse Schur solver at
// every size and Ceres' convergence test (relative cost change below 1e-6;
// COLMAP switches to an iterative solver above 1,000 images and runs its
// global adjustments to the iteration limit). Returns the solver's name and
// Ceres' one-line report, empty when there was nothing to adjust.
std::string AdjustWholeModel(const colmap::BundleAdjustmentOptions& options,
                             colmap::Reconstruction* model);

// The points of `model` that are among the points_per_image longest tracks
// of some registered image, sorted.
std::vector<colmap::point3D_t> LongestTrackPoints(
    const colmap::Reconstruction& model, size_t points_per_image);

// The registered images of `model` with only its LongestTrackPoints (ids
// kept): the points that tie a large model together.
colmap::Reconstruction ModelOfLongestTracks(const colmap::Reconstruction& model,
                                            size_t points_per_image);

// Global bundle adjustment of every pose and camera on the model's
// points_per_image longest tracks per image only (ModelOfLongestTracks,
// AdjustWholeModel); a point left out moves with the first image that
// observes it, then is triangulated again with the adjusted poses where
// that fits its observations better (on a city with a misaligned half, the
// rigid move alone left 8% of the points to be filtered, against 2% after
// the whole adjustment; triangulated again, 2%). It fixes the
// large-scale shape at a part of the whole problem's cost, not the fine detail.
// Returns a one-line report.
std::string AdjustOnLongestTracks(
    const colmap::BundleAdjustmentOptions& options, size_t points_per_image,
    colmap::Reconstruction* model);

// Bundle adjustment of a large model in two steps whose memory is a part of
// the whole problem's: (1) every pose and camera adjusted together on the
// 500 longest tracks of each image (AdjustOnLongestTracks),
// which closes the model's loops and fixes its large-scale shape; (2) one
// pass over blocks of at most max_block_images (CovisibleImageBlocks), each
// adjusted with all its points (AdjustBlock), which fits the points left
// out of step 1 and the fine detail. Block passes alone converge slowly on
// the large-scale shape (docs/benchmarks.md). Returns a
// one-line report.
std::string AdjustByBlocks(const colmap::BundleAdjustmentOptions& options,
                           size_t max_block_images,
                           colmap::Reconstruction* model);

}  // namespace tmr
