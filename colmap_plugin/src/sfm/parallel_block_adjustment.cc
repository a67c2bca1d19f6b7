// Copyright (c) 2026, the tmr authors. BSD-3-Clause.
#include "sfm/parallel_block_adjustment.h"

#include <colmap/util/threading.h>

#include <algorithm>
#include <chrono>
#include <future>
#include <map>
#include <memory>
#include <sstream>
#include <unordered_map>
#include <unordered_set>

#include "sfm/block_adjustment.h"
#include "sfm/model_edits.h"
#include "tmr/util/futures.h"
#include "tmr/util/process.h"

namespace tmr {
namespace {

// The part of `model` that a block's adjustment reads: the block's images,
// every point they observe, and the other images of those points' tracks
// (with only those points), all at their current poses.
std::unique_ptr<colmap::Reconstruction> BlockPart(
    const colmap::Reconstruction& model,
    const std::vector<colmap::image_t>& block) {
  auto part = std::make_unique<colmap::Reconstruction>();
  std::vector<colmap::point3D_t> points;
  for (const colmap::image_t id : block) {
    const colmap::Image& image = model.Image(id);
    AddImageWithoutPoints(model, id, image.CamFromWorld(), part.get());
    for (const colmap::Point2D& point2D : image.Points2D())
      if (point2D.HasPoint3D()) points.push_back(point2D.point3D_id);
  }
  std::sort(points.begin(), points.end());
  points.erase(std::unique(points.begin(), points.end()), points.end());
  CopyPointsWithTracks(model, points, part.get());
  return part;
}

}  // namespace

std::string BlocksAdjustment::Describe() const {
  std::ostringstream out;
  out << block_seconds.size() << " blocks adjusted at once ("
      << totals.Describe() << ")";
  return out.str();
}

BlocksAdjustment AdjustBlocksAtOnce(
    const std::vector<std::vector<colmap::image_t>>& blocks,
    const colmap::BundleAdjustmentOptions& options, int num_workers,
    colmap::Reconstruction* model) {
  const auto start = std::chrono::steady_clock::now();
  const int num_blocks = static_cast<int>(blocks.size());
  std::unordered_map<colmap::image_t, int> block_of;
  std::map<colmap::camera_t, std::unordered_set<int>> camera_blocks;
  for (int b = 0; b < num_blocks; ++b) {
    for (const colmap::image_t id : blocks[b]) {
      block_of[id] = b;
      camera_blocks[model->Image(id).CameraId()].insert(b);
    }
  }
  std::unordered_set<colmap::camera_t> shared_cameras;
  for (const auto& [camera_id, in_blocks] : camera_blocks)
    if (in_blocks.size() > 1) shared_cameras.insert(camera_id);

  // Every block reads the model as it was; nothing is written until all
  // are done.
  BlocksAdjustment result;
  result.block_seconds.resize(num_blocks);
  std::vector<std::unique_ptr<colmap::Reconstruction>> parts(num_blocks);
  std::vector<BlockAdjustment> adjusted(num_blocks);
  {
    colmap::ThreadPool pool(std::max(1, std::min(num_workers, num_blocks)));
    std::vector<std::shared_future<void>> done;
    for (int b = 0; b < num_blocks; ++b) {
      done.push_back(pool.AddTask([&, b] {
        const auto block_start = std::chrono::steady_clock::now();
        parts[b] = BlockPart(*model, blocks[b]);
        adjusted[b] =
            AdjustBlock(blocks[b], options, parts[b].get(), shared_cameras);
        result.block_seconds[b] = SecondsSince(block_start);
      }));
    }
    WaitForAll(done);
  }

  std::vector<colmap::point3D_t> seam_points;
  for (const auto& [point_id, point] : model->Points3D()) {
    std::map<int, int> observations;  // per block
    for (const colmap::TrackElement& element : point.track.Elements()) {
      const auto it = block_of.find(element.image_id);
      if (it != block_of.end()) ++observations[it->second];
    }
    if (observations.empty()) continue;
    int owner = observations.begin()->first;
    for (const auto& [b, count] : observations)
      if (count > observations[owner]) owner = b;
    model->Point3D(point_id).xyz = parts[owner]->Point3D(point_id).xyz;
    if (observations.size() > 1) seam_points.push_back(point_id);
  }
  for (int b = 0; b < num_blocks; ++b) {
    const colmap::Reconstruction& part = *parts[b];
    for (const colmap::image_t id : blocks[b]) {
      SetPoseAndRegister(id, part.Image(id).CamFromWorld(), model);
      const colmap::camera_t camera_id = model->Image(id).CameraId();
      if (!shared_cameras.count(camera_id))
        model->Camera(camera_id).params = part.Camera(camera_id).params;
    }
    result.totals.Add(adjusted[b]);
  }
  parts.clear();
  std::sort(seam_points.begin(), seam_points.end());
  for (const colmap::point3D_t point_id : seam_points)
    RetriangulateIfBetter(model, point_id);
  result.seconds = SecondsSince(start);
  return result;
}

}  // namespace tmr
