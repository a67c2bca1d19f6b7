// Copyright (c) 2026, the tmr authors. BSD-3-Clause.
#include "sfm/block_adjustment.h"

#include <colmap/estimators/bundle_adjustment_ceres.h>
#include <colmap/geometry/triangulation.h>
#include <colmap/scene/projection.h>
#include <colmap/util/threading.h>

#include <algorithm>
#include <functional>
#include <future>
#include <limits>
#include <memory>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <unordered_map>
#include <unordered_set>

#include "sfm/model_edits.h"
#include "tmr/util/futures.h"

namespace tmr {
namespace {

// Sum of the squared reprojection errors (px^2) of `xyz` over its track;
// infinite when it lies behind a camera.
double SquaredReprojectionError(const colmap::Reconstruction& model,
                                const colmap::Track& track,
                                const Eigen::Vector3d& xyz) {
  double sum = 0;
  for (const colmap::TrackElement& element : track.Elements()) {
    const colmap::Image& image = model.Image(element.image_id);
    // COLMAP's value for a point behind the camera is the largest double.
    const double error = colmap::CalculateSquaredReprojectionError(
        image.Point2D(element.point2D_idx).xy, xyz, image.CamFromWorld(),
        model.Camera(image.CameraId()));
    if (error == std::numeric_limits<double>::max())
      return std::numeric_limits<double>::infinity();
    sum += error;
  }
  return sum;
}

// Calls visit(other) for every registered image that shares a 3D point with
// `image_id` (once per shared observation).
template <typename Visit>
void ForEachCovisibleImage(const colmap::Reconstruction& model,
                           colmap::image_t image_id, const Visit& visit) {
  for (const colmap::Point2D& point2D : model.Image(image_id).Points2D()) {
    if (!point2D.HasPoint3D()) continue;
    for (const colmap::TrackElement& element :
         model.Point3D(point2D.point3D_id).track.Elements()) {
      if (element.image_id != image_id) visit(element.image_id);
    }
  }
}

// Breadth-first order over images not yet `taken` (marked taken as they are
// reached), from `seed`, stopping after max_images.
std::vector<colmap::image_t> GrowBreadthFirst(
    const colmap::Reconstruction& model, colmap::image_t seed,
    size_t max_images, std::unordered_set<colmap::image_t>* taken) {
  std::vector<colmap::image_t> order = {seed};
  taken->insert(seed);
  for (size_t next = 0; next < order.size() && order.size() < max_images;
       ++next) {
    ForEachCovisibleImage(model, order[next], [&](colmap::image_t other) {
      if (order.size() < max_images && model.Image(other).HasPose() &&
          taken->insert(other).second) {
        order.push_back(other);
      }
    });
  }
  return order;
}

// COLMAP's adjustment (residuals, loss) of `config` on `model` with a
// direct sparse Schur solver at every size (COLMAP switches to an
// iterative one above 1,000 images) and Ceres' convergence test (relative
// cost change below 1e-6; COLMAP's global adjustments run to the iteration
// limit). Nothing when the problem has no residuals.
std::optional<ceres::Solver::Summary> Solve(
    colmap::BundleAdjustmentOptions options,
    const colmap::BundleAdjustmentConfig& config,
    colmap::Reconstruction* model) {
  if (config.NumResiduals(*model) == 0) return std::nullopt;
  options.print_summary = false;
  options.ceres->max_num_images_direct_sparse_cpu_solver =
      std::numeric_limits<int>::max();
  options.ceres->solver_options.function_tolerance = 1e-6;
  const std::shared_ptr<colmap::BundleAdjustmentSummary> summary =
      colmap::CreateDefaultCeresBundleAdjuster(options, config, *model)
          ->Solve();
  const auto* ceres_summary =
      dynamic_cast<const colmap::CeresBundleAdjustmentSummary*>(summary.get());
  if (ceres_summary == nullptr) return std::nullopt;
  return ceres_summary->ceres_summary;
}

}  // namespace

void RetriangulateIfBetter(colmap::Reconstruction* model,
                           colmap::point3D_t point_id) {
  colmap::Point3D& point = model->Point3D(point_id);
  std::vector<Eigen::Matrix3x4d> cams_from_world;
  std::vector<Eigen::Vector2d> normalized;
  for (const colmap::TrackElement& element : point.track.Elements()) {
    const colmap::Image& image = model->Image(element.image_id);
    cams_from_world.push_back(image.CamFromWorld().ToMatrix());
    const std::optional<Eigen::Vector2d> cam_point =
        model->Camera(image.CameraId())
            .CamFromImg(image.Point2D(element.point2D_idx).xy);
    if (!cam_point) return;
    normalized.push_back(*cam_point);
  }
  Eigen::Vector3d xyz;
  if (colmap::TriangulateMultiViewPoint(
          colmap::span<const Eigen::Matrix3x4d>(cams_from_world.data(),
                                                cams_from_world.size()),
          colmap::span<const Eigen::Vector2d>(normalized.data(),
                                              normalized.size()),
          &xyz) &&
      xyz.allFinite() &&
      SquaredReprojectionError(*model, point.track, xyz) <
          SquaredReprojectionError(*model, point.track, point.xyz))
    point.xyz = xyz;
}

void BlockAdjustmentTotals::Add(const BlockAdjustment& block) {
  num_converged += block.converged ? 1 : 0;
  num_iterations += block.num_iterations;
  initial_cost += block.initial_cost;
  final_cost += block.final_cost;
}

std::string BlockAdjustmentTotals::Describe() const {
  std::ostringstream out;
  out << num_converged << " converged, " << num_iterations
      << " iterations, cost " << initial_cost << " -> " << final_cost;
  return out.str();
}

std::vector<std::vector<colmap::image_t>> CovisibleImageBlocks(
    const colmap::Reconstruction& model, size_t max_images) {
  if (max_images == 0)
    throw std::invalid_argument("CovisibleImageBlocks: max_images is 0");
  std::vector<colmap::image_t> ids = model.RegImageIds();
  std::sort(ids.begin(), ids.end());
  // Seed order: the whole model breadth-first, component after component.
  std::vector<colmap::image_t> seeds;
  std::unordered_set<colmap::image_t> reached;
  for (const colmap::image_t id : ids) {
    if (reached.count(id)) continue;
    const auto component = GrowBreadthFirst(model, id, ids.size(), &reached);
    seeds.insert(seeds.end(), component.begin(), component.end());
  }
  std::vector<std::vector<colmap::image_t>> blocks;
  std::unordered_set<colmap::image_t> taken;
  for (const colmap::image_t seed : seeds) {
    if (!taken.count(seed))
      blocks.push_back(GrowBreadthFirst(model, seed, max_images, &taken));
  }
  return blocks;
}

BlockAdjustment AdjustBlock(
    const std::vector<colmap::image_t>& block,
    const colmap::BundleAdjustmentOptions& options,
    colmap::Reconstruction* model,
    const std::unordered_set<colmap::camera_t>& held_cameras) {
  BlockAdjustment result;
  if (block.empty()) return result;
  const std::unordered_set<colmap::image_t> inside(block.begin(), block.end());
  colmap::BundleAdjustmentConfig config;
  for (const colmap::camera_t id : held_cameras)
    config.SetConstantCamIntrinsics(id);
  for (const colmap::image_t id : block) {
    config.AddImage(id);
    for (const colmap::Point2D& point2D : model->Image(id).Points2D()) {
      if (!point2D.HasPoint3D() || config.HasVariablePoint(point2D.point3D_id))
        continue;
      for (const colmap::TrackElement& element :
           model->Point3D(point2D.point3D_id).track.Elements()) {
        if (!inside.count(element.image_id)) {
          config.AddVariablePoint(point2D.point3D_id);
          break;
        }
      }
    }
  }
  if (config.NumVariablePoints() == 0)
    config.FixGauge(colmap::BundleAdjustmentGauge::TWO_CAMS_FROM_WORLD);
  const auto summary = Solve(options, config, model);
  if (!summary) return result;
  result.num_iterations = static_cast<int>(summary->iterations.size()) - 1;
  result.converged = summary->termination_type == ceres::CONVERGENCE;
  result.initial_cost = summary->initial_cost;
  result.final_cost = summary->final_cost;
  return result;
}

std::string AdjustWholeModel(const colmap::BundleAdjustmentOptions& options,
                             colmap::Reconstruction* model) {
  const std::vector<colmap::image_t> images = model->RegImageIds();
  if (images.size() < 2) return "";
  colmap::BundleAdjustmentConfig config;
  for (const colmap::image_t id : images) config.AddImage(id);
  config.FixGauge(colmap::BundleAdjustmentGauge::TWO_CAMS_FROM_WORLD);
  const auto summary = Solve(options, config, model);
  if (!summary) return "";
  return std::string(ceres::LinearSolverTypeToString(
             summary->linear_solver_type_used)) +
         ": " + summary->BriefReport();
}

std::vector<colmap::point3D_t> LongestTrackPoints(
    const colmap::Reconstruction& model, size_t points_per_image) {
  std::unordered_set<colmap::point3D_t> kept;
  std::vector<std::pair<size_t, colmap::point3D_t>> by_length;
  for (const colmap::image_t id : model.RegImageIds()) {
    by_length.clear();
    for (const colmap::Point2D& point2D : model.Image(id).Points2D()) {
      if (point2D.HasPoint3D()) {
        by_length.emplace_back(model.Point3D(point2D.point3D_id).track.Length(),
                               point2D.point3D_id);
      }
    }
    const size_t n = std::min(points_per_image, by_length.size());
    std::partial_sort(by_length.begin(), by_length.begin() + n, by_length.end(),
                      std::greater<>());
    for (size_t i = 0; i < n; ++i) kept.insert(by_length[i].second);
  }
  std::vector<colmap::point3D_t> ids(kept.begin(), kept.end());
  std::sort(ids.begin(), ids.end());
  return ids;
}

void MoveToPoses(
    const std::unordered_map<colmap::image_t, colmap::Rigid3d>& cam_from_world,
    const std::vector<colmap::point3D_t>& point_ids,
    colmap::Reconstruction* model, int num_threads) {
  for (const colmap::point3D_t point_id : point_ids) {
    colmap::Point3D& point = model->Point3D(point_id);
    const colmap::image_t id = point.track.Element(0).image_id;
    const auto moved = cam_from_world.find(id);
    if (moved == cam_from_world.end()) continue;
    point.xyz = colmap::Inverse(moved->second) *
                (model->Image(id).CamFromWorld() * point.xyz);
  }
  for (const colmap::image_t id : model->RegImageIds()) {
    const auto moved = cam_from_world.find(id);
    if (moved != cam_from_world.end())
      SetPoseAndRegister(id, moved->second, model);
  }
  // Each point's triangulation reads the poses and writes only that point.
  const size_t workers = static_cast<size_t>(std::max(1, num_threads));
  const size_t chunk = (point_ids.size() + workers - 1) / workers;
  colmap::ThreadPool pool(static_cast<int>(workers));
  std::vector<std::shared_future<void>> done;
  for (size_t begin = 0; begin < point_ids.size(); begin += chunk) {
    const size_t end = std::min(point_ids.size(), begin + chunk);
    done.push_back(pool.AddTask([&, begin, end] {
      for (size_t i = begin; i < end; ++i)
        RetriangulateIfBetter(model, point_ids[i]);
    }));
  }
  WaitForAll(done);
}

colmap::Reconstruction ModelOfLongestTracks(const colmap::Reconstruction& model,
                                            size_t points_per_image) {
  colmap::Reconstruction reduced;
  for (const colmap::image_t id : model.RegImageIds())
    AddImageWithoutPoints(model, id, model.Image(id).CamFromWorld(), &reduced);
  CopyPointsWithTracks(model, LongestTrackPoints(model, points_per_image),
                       &reduced);
  return reduced;
}

std::string AdjustOnLongestTracks(
    const colmap::BundleAdjustmentOptions& options, size_t points_per_image,
    colmap::Reconstruction* model) {
  colmap::Reconstruction reduced =
      ModelOfLongestTracks(*model, points_per_image);
  std::ostringstream report;
  report << "global on " << reduced.NumPoints3D() << " of "
         << model->NumPoints3D() << " points ("
         << AdjustWholeModel(options, &reduced) << ")";
  for (const auto& [camera_id, camera] : reduced.Cameras())
    model->Camera(camera_id).params = camera.params;
  for (const auto& [point_id, point] : reduced.Points3D())
    model->Point3D(point_id).xyz = point.xyz;
  // A point left out moves with the first image that observes it, then is
  // triangulated again with the adjusted poses where that fits better.
  std::vector<colmap::point3D_t> left_out;
  for (const auto& [point_id, point] : model->Points3D())
    if (!reduced.ExistsPoint3D(point_id)) left_out.push_back(point_id);
  std::unordered_map<colmap::image_t, colmap::Rigid3d> adjusted;
  for (const colmap::image_t id : reduced.RegImageIds())
    adjusted[id] = reduced.Image(id).CamFromWorld();
  MoveToPoses(adjusted, left_out, model);
  return report.str();
}

std::string AdjustByBlocks(const colmap::BundleAdjustmentOptions& options,
                           size_t max_block_images,
                           colmap::Reconstruction* model) {
  // Long tracks tie the model together; 500 per image came within 0.003
  // deg of the whole adjustment (docs/benchmarks.md).
  constexpr size_t kGlobalPointsPerImage = 500;
  std::ostringstream report;
  report << AdjustOnLongestTracks(options, kGlobalPointsPerImage, model);
  const auto blocks = CovisibleImageBlocks(*model, max_block_images);
  BlockAdjustmentTotals totals;
  for (const auto& block : blocks)
    totals.Add(AdjustBlock(block, options, model));
  report << ", then " << blocks.size() << " blocks of at most "
         << max_block_images << " images (" << totals.Describe() << ")";
  return report.str();
}

}  // namespace tmr
