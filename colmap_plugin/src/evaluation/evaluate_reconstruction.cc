// Copyright (c) 2026, the tmr authors. BSD-3-Clause.
#include "evaluation/evaluate_reconstruction.h"

#include <colmap/estimators/alignment.h>
#include <colmap/estimators/solvers/similarity_transform.h>
#include <colmap/geometry/sim3.h>
#include <colmap/math/math.h>
#include <colmap/optim/loransac.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <random>
#include <stdexcept>

#include "io/model_files.h"
#include "io/task_database.h"
#include "sfm/match_consistency.h"

namespace tmr {
namespace {

using Sim3Ransac =
    colmap::LORANSAC<colmap::SimilarityTransformEstimator<3, true>,
                     colmap::SimilarityTransformEstimator<3, true>>;
constexpr int kMaxTrackLengthBin = 30;

double Quantile(std::vector<double> values, double q) {
  if (values.empty()) return 0.0;
  const size_t k = static_cast<size_t>(std::lround(q * (values.size() - 1)));
  std::nth_element(values.begin(), values.begin() + k, values.end());
  return values[k];
}

ErrorStatistics Statistics(const std::vector<double>& values) {
  ErrorStatistics s;
  s.median = Quantile(values, 0.5);
  s.p90 = Quantile(values, 0.9);
  s.max =
      values.empty() ? 0.0 : *std::max_element(values.begin(), values.end());
  return s;
}

// Robust sim3 from model centres to reference centres; false if none fits.
bool AlignCentres(const std::vector<Eigen::Vector3d>& model,
                  const std::vector<Eigen::Vector3d>& reference,
                  double max_error, int min_inliers, unsigned seed,
                  colmap::Sim3d* ref_from_model,
                  std::vector<char>* inlier_mask) {
  if (model.size() < 3) return false;
  colmap::RANSACOptions ransac;
  ransac.max_error = max_error;
  ransac.min_inlier_ratio = 0.05;
  ransac.max_num_trials = 2000;
  ransac.random_seed = static_cast<int>(seed);
  Sim3Ransac estimator(ransac);
  const auto report = estimator.Estimate(model, reference);
  if (!report.success ||
      static_cast<int>(report.support.num_inliers) < min_inliers) {
    return false;
  }
  *ref_from_model = colmap::Sim3d::FromMatrix(report.model);
  *inlier_mask = report.inlier_mask;
  return true;
}

// Rotation errors after the rotation that best maps the model's camera
// orientations onto the reference's: the quaternion mean of the per-image
// reference-from-model rotations over the centre alignment's inliers, then
// over the images within 3x the median error (three rounds). Aligning on
// the centres alone ties the rotation to how well the centres constrain it:
// on a 60-photo place ringed by cameras it was off by up to 0.1 degrees,
// more than the orientation errors it measured (docs/benchmarks.md,
// "How rotation errors are measured").
std::vector<double> RotationAlignedErrorsDeg(
    const colmap::Reconstruction& model,
    const colmap::Reconstruction& reference,
    const std::vector<std::pair<colmap::image_t, colmap::image_t>>& common,
    const std::vector<char>& inliers) {
  std::vector<Eigen::Quaterniond> ref_from_model(common.size());
  for (size_t k = 0; k < common.size(); ++k) {
    ref_from_model[k] =
        reference.Image(common[k].second).CamFromWorld().rotation().inverse() *
        model.Image(common[k].first).CamFromWorld().rotation();
  }
  std::vector<char> used = inliers;
  std::vector<double> errors(common.size(), 0.0);
  for (int round = 0; round < 3; ++round) {
    Eigen::Vector4d sum = Eigen::Vector4d::Zero();
    const Eigen::Quaterniond* first = nullptr;
    for (size_t k = 0; k < common.size(); ++k) {
      if (!used[k]) continue;
      if (first == nullptr) first = &ref_from_model[k];
      const double sign = first->dot(ref_from_model[k]) < 0 ? -1.0 : 1.0;
      sum += sign * ref_from_model[k].coeffs();
    }
    if (first == nullptr) break;
    const Eigen::Quaterniond mean(Eigen::Vector4d(sum.normalized()));
    for (size_t k = 0; k < common.size(); ++k) {
      errors[k] = colmap::RadToDeg(mean.angularDistance(ref_from_model[k]));
    }
    std::vector<double> kept;
    for (size_t k = 0; k < common.size(); ++k)
      if (used[k]) kept.push_back(errors[k]);
    const double limit = 3.0 * Quantile(kept, 0.5);
    for (size_t k = 0; k < common.size(); ++k) used[k] = errors[k] <= limit;
  }
  return errors;
}

}  // namespace

bool ModelEvaluationOptions::Check(std::string* error) const {
  auto fail = [&](const std::string& message) {
    if (error) *error = message;
    return false;
  };
  if (inlier_threshold <= 0) return fail("inlier_threshold must be > 0");
  if (displaced_threshold <= inlier_threshold) {
    return fail("displaced_threshold must be > inlier_threshold");
  }
  if (min_wrong_merge_images < 3)
    return fail("min_wrong_merge_images must be >= 3");
  return match_consistency.Check(error);
}

ModelEvaluation EvaluateReconstruction(const colmap::Reconstruction& reference,
                                       const colmap::Reconstruction& model,
                                       const ModelEvaluationOptions& options) {
  std::string error;
  if (!options.Check(&error)) throw std::invalid_argument(error);
  ModelEvaluation eval;
  eval.num_registered_images = static_cast<int>(model.NumRegImages());
  eval.num_points3D = static_cast<int>(model.NumPoints3D());
  eval.mean_reprojection_error_px = model.ComputeMeanReprojectionError();
  eval.mean_track_length = model.ComputeMeanTrackLength();
  eval.track_length_histogram.assign(kMaxTrackLengthBin + 1, 0);
  for (const auto& [id, point] : model.Points3D()) {
    ++eval.track_length_histogram[std::min<size_t>(point.track.Length(),
                                                   kMaxTrackLengthBin)];
  }

  for (const colmap::image_t id : model.RegImageIds())
    eval.image_names.push_back(model.Image(id).Name());
  eval.num_reference_images = static_cast<int>(reference.NumRegImages());
  const auto common = model.FindCommonRegImageIds(reference);
  eval.num_common_images = static_cast<int>(common.size());
  std::vector<Eigen::Vector3d> model_centres, reference_centres;
  for (const auto& [model_id, reference_id] : common) {
    model_centres.push_back(model.Image(model_id).ProjectionCenter());
    reference_centres.push_back(
        reference.Image(reference_id).ProjectionCenter());
  }
  if (common.size() < 3) return eval;
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
  for (const auto& c : reference_centres) centroid += c;
  centroid /= reference_centres.size();
  double sum2 = 0.0;
  for (const auto& c : reference_centres) sum2 += (c - centroid).squaredNorm();
  eval.scene_scale = std::sqrt(sum2 / reference_centres.size());
  if (eval.scene_scale <= 0) return eval;

  colmap::Sim3d ref_from_model;
  std::vector<char> inliers;
  if (!AlignCentres(model_centres, reference_centres,
                    options.inlier_threshold * eval.scene_scale, 3,
                    options.seed, &ref_from_model, &inliers)) {
    return eval;
  }
  eval.aligned = true;
  eval.num_alignment_inliers =
      static_cast<int>(std::count(inliers.begin(), inliers.end(), 1));

  const auto errors =
      colmap::ComputeImageAlignmentError(model, reference, ref_from_model);
  std::vector<double> centre_aligned_rotation, position;
  std::vector<Eigen::Vector3d> displaced_model, displaced_reference;
  std::vector<std::pair<double, std::string>> displaced_names;
  for (size_t k = 0; k < errors.size(); ++k) {
    centre_aligned_rotation.push_back(errors[k].rotation_error_deg);
    position.push_back(errors[k].proj_center_error / eval.scene_scale);
    if (position.back() > options.displaced_threshold) {
      displaced_model.push_back(model_centres[k]);
      displaced_reference.push_back(reference_centres[k]);
      displaced_names.emplace_back(-position.back(), errors[k].image_name);
    }
  }
  std::sort(displaced_names.begin(), displaced_names.end());
  for (const auto& [error, name] : displaced_names)
    eval.displaced_image_names.push_back(name);
  for (const colmap::image_t id : model.RegImageIds()) {
    const Eigen::Vector3d c =
        ref_from_model * model.Image(id).ProjectionCenter();
    eval.aligned_centres.push_back({c.x(), c.y(), c.z()});
  }
  eval.rotation_error_deg =
      Statistics(RotationAlignedErrorsDeg(model, reference, common, inliers));
  eval.centre_aligned_rotation_error_deg = Statistics(centre_aligned_rotation);
  eval.position_error = Statistics(position);
  eval.num_displaced_images = static_cast<int>(displaced_model.size());

  // A wrong merge: the displaced images form a rigid part of their own.
  colmap::Sim3d part_from_model;
  std::vector<char> part_inliers;
  if (eval.num_displaced_images >= options.min_wrong_merge_images &&
      AlignCentres(displaced_model, displaced_reference,
                   options.inlier_threshold * eval.scene_scale,
                   options.min_wrong_merge_images, options.seed,
                   &part_from_model, &part_inliers)) {
    eval.wrong_merge = true;
    std::vector<double> offsets;
    for (size_t k = 0; k < displaced_model.size(); ++k) {
      if (!part_inliers[k]) continue;
      offsets.push_back(
          (ref_from_model * displaced_model[k] - displaced_reference[k])
              .norm() /
          eval.scene_scale);
    }
    eval.displacement = Quantile(offsets, 0.5);
    eval.displacement_rotation_deg = colmap::RadToDeg(
        ref_from_model.rotation().angularDistance(part_from_model.rotation()));
  }
  return eval;
}

std::vector<std::array<double, 3>> ReadCameraCentres(
    const std::string& model_path) {
  const colmap::Reconstruction model = ReadModel(model_path);
  std::vector<std::array<double, 3>> centres;
  for (const colmap::image_t id : model.RegImageIds()) {
    const Eigen::Vector3d c = model.Image(id).ProjectionCenter();
    centres.push_back({c.x(), c.y(), c.z()});
  }
  return centres;
}

namespace {

MatchConsistency CheckMatchConsistency(const colmap::Reconstruction& model,
                                       const std::string& database_path,
                                       const MatchConsistencyOptions& options) {
  namespace fs = std::filesystem;
  // COLMAP's Database class writes to what it opens: the model's images
  // are copied into a temporary database first (the input stays read-only).
  std::vector<uint32_t> image_ids;
  for (const colmap::image_t id : model.RegImageIds()) image_ids.push_back(id);
  const fs::path scratch =
      fs::temp_directory_path() /
      ("tmr_eval_" + std::to_string(std::random_device()()) + ".db");
  std::string error;
  if (!WriteTaskDatabase(database_path, image_ids, scratch.string(), &error))
    throw std::runtime_error(error);
  std::optional<MatchConsistency> result;
  try {
    const std::shared_ptr<colmap::Database> database =
        colmap::Database::Open(scratch.string());
    result = CheckMatchConsistency(model, *database, options);
  } catch (const std::exception& e) {
    error = e.what();
  }
  std::error_code ec;
  fs::remove(scratch, ec);
  if (!result) throw std::runtime_error(error);
  return *result;
}

}  // namespace

ModelEvaluation EvaluateModel(const std::string& reference_path,
                              const std::string& model_path,
                              const ModelEvaluationOptions& options) {
  const colmap::Reconstruction reference = reference_path.empty()
                                               ? colmap::Reconstruction()
                                               : ReadModel(reference_path);
  const colmap::Reconstruction model = ReadModel(model_path);
  ModelEvaluation eval = EvaluateReconstruction(reference, model, options);
  eval.model_path = model_path;
  if (!options.database_path.empty()) {
    eval.match_consistency = CheckMatchConsistency(
        model, options.database_path, options.match_consistency);
    eval.match_consistent =
        eval.match_consistency->IsConsistent(options.match_consistency);
  }
  return eval;
}

}  // namespace tmr
