// Copyright (c) 2026, the tmr authors. BSD-3-Clause.
#include "tmr/colmap/synthetic_scene.h"

#include <colmap/estimators/two_view_geometry.h>
#include <colmap/scene/database.h>
#include <colmap/scene/reconstruction.h>
#include <colmap/util/threading.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <future>
#include <numeric>
#include <random>
#include <sstream>
#include <vector>

#include "synthetic/observations.h"
#include "synthetic/scene_layout.h"
#include "tmr/util/futures.h"

namespace tmr {
namespace {

namespace fs = std::filesystem;
using synthetic::ImageIntrinsics;
using synthetic::ImageKeypoints;
using synthetic::ImagePairMatches;

std::string ImageName(const std::string& part, int index) {
  char number[16];
  std::snprintf(number, sizeof(number), "%06d", index);
  return part + "/" + number + ".jpg";
}

colmap::Camera MakeCamera(const ImageIntrinsics& k, double focal_px) {
  colmap::Camera camera = colmap::Camera::CreateFromModelName(
      colmap::kInvalidCameraId, "SIMPLE_RADIAL", focal_px, k.width, k.height);
  camera.has_prior_focal_length = true;
  return camera;
}

// Raw matches: the inliers plus random outlier pairs of keypoints.
colmap::FeatureMatches RawMatches(const ImagePairMatches& pair, int n1, int n2,
                                  const SyntheticSceneOptions& options) {
  colmap::FeatureMatches matches;
  for (const auto& m : pair.inliers)
    matches.emplace_back(m.keypoint1, m.keypoint2);
  const int num_outliers = static_cast<int>(
      std::lround(options.outlier_match_ratio * pair.inliers.size()));
  for (int j = 0; j < num_outliers; ++j) {
    const double u1 =
        synthetic::HashUniform(options.seed, pair.image1, pair.image2, 2 * j);
    const double u2 = synthetic::HashUniform(options.seed, pair.image1,
                                             pair.image2, 2 * j + 1);
    matches.emplace_back(static_cast<uint32_t>(u1 * n1),
                         static_cast<uint32_t>(u2 * n2));
  }
  return matches;
}

// A verified pair as COLMAP's matcher writes it: the pair's matches, with
// the configuration and the E, F and H that COLMAP's two-view estimator
// (EstimateCalibratedTwoViewGeometry, default options) finds on them from
// the keypoints and the database's camera priors; no relative pose, which
// COLMAP 4's global mapper decomposes from E itself. The matches written are
// the scene's own, not the estimator's inlier subset, so that the match
// statistics stay as generated. A pair the estimator rejects (the random
// matches of a false pair) keeps CALIBRATED without matrices: as a wrong
// pair that passed verification, whose geometry a reader fits itself.
colmap::TwoViewGeometry VerifiedGeometry(
    const ImagePairMatches& pair, const std::vector<colmap::Camera>& cameras,
    const std::vector<ImageKeypoints>& keypoints, uint64_t seed) {
  colmap::TwoViewGeometry geometry;
  for (const auto& m : pair.inliers) {
    geometry.inlier_matches.emplace_back(m.keypoint1, m.keypoint2);
  }
  colmap::TwoViewGeometryOptions options;
  options.ransac_options.random_seed = static_cast<int>(
      synthetic::HashUniform(seed, pair.image1, pair.image2, 0xe) * 1e9);
  const colmap::TwoViewGeometry estimate =
      colmap::EstimateCalibratedTwoViewGeometry(
          cameras[pair.image1], keypoints[pair.image1].xy, cameras[pair.image2],
          keypoints[pair.image2].xy, geometry.inlier_matches, options);
  geometry.config = colmap::TwoViewGeometry::CALIBRATED;
  if (estimate.config != colmap::TwoViewGeometry::DEGENERATE &&
      estimate.config != colmap::TwoViewGeometry::UNDEFINED) {
    geometry.config = estimate.config;
    geometry.E = estimate.E;
    geometry.F = estimate.F;
    geometry.H = estimate.H;
  }
  return geometry;
}

// The ground truth: true cameras and poses, and the points that take part in
// at least two matched detections.
colmap::Reconstruction GroundTruth(
    const synthetic::SceneLayout& layout,
    const std::vector<synthetic::ScenePoint>& points,
    const std::vector<ImageIntrinsics>& intrinsics,
    const std::vector<ImageKeypoints>& keypoints,
    const std::vector<ImagePairMatches>& pairs,
    const std::vector<std::string>& names) {
  colmap::Reconstruction gt;
  const int num_images = static_cast<int>(names.size());
  for (int i = 0; i < num_images; ++i) {
    colmap::Camera camera = MakeCamera(intrinsics[i], intrinsics[i].focal_px);
    camera.camera_id = i + 1;
    gt.AddCameraWithTrivialRig(camera);
    colmap::Image image;
    image.SetImageId(i + 1);
    image.SetCameraId(i + 1);
    image.SetName(names[i]);
    image.SetPoints2D(keypoints[i].xy);
    const Eigen::Quaterniond rotation(layout.cameras[i].cam_from_world);
    gt.AddImageWithTrivialFrame(
        std::move(image),
        colmap::Rigid3d(rotation, -(layout.cameras[i].cam_from_world *
                                    layout.cameras[i].center)));
  }
  // Tracks: detections that take part in a true verified match.
  std::vector<std::vector<bool>> matched(num_images);
  for (int i = 0; i < num_images; ++i) {
    matched[i].assign(keypoints[i].xy.size(), false);
  }
  for (const ImagePairMatches& pair : pairs) {
    if (pair.is_false) continue;
    for (const auto& m : pair.inliers) {
      matched[pair.image1][m.keypoint1] = true;
      matched[pair.image2][m.keypoint2] = true;
    }
  }
  std::vector<colmap::Track> tracks(points.size());
  for (int i = 0; i < num_images; ++i) {
    for (uint32_t k = 0; k < keypoints[i].point.size(); ++k) {
      const int p = keypoints[i].point[k];
      if (p >= 0 && matched[i][k]) tracks[p].AddElement(i + 1, k);
    }
  }
  for (size_t p = 0; p < points.size(); ++p) {
    if (tracks[p].Length() >= 2) gt.AddPoint3D(points[p].xyz, tracks[p]);
  }
  return gt;
}

// Writes the database as COLMAP's feature extraction and matching would:
// per image its camera (with the prior focal length), rig, image, frame and
// keypoints, then per pair its raw matches and verified geometry.
void WriteDatabase(const std::string& database_path,
                   const SyntheticSceneOptions& options,
                   const std::vector<ImageIntrinsics>& intrinsics,
                   const std::vector<double>& prior_focal,
                   const std::vector<std::string>& names,
                   const std::vector<ImageKeypoints>& keypoints,
                   const std::vector<ImagePairMatches>& pairs) {
  const int num_images = static_cast<int>(names.size());
  const std::shared_ptr<colmap::Database> database =
      colmap::Database::Open(database_path);
  colmap::DatabaseTransaction transaction(database.get());
  std::vector<colmap::Camera> cameras;
  cameras.reserve(num_images);
  for (int i = 0; i < num_images; ++i) {
    colmap::Camera& camera =
        cameras.emplace_back(MakeCamera(intrinsics[i], prior_focal[i]));
    camera.camera_id = database->WriteCamera(camera);
    colmap::Rig rig;
    rig.AddRefSensor(camera.SensorId());
    const colmap::rig_t rig_id = database->WriteRig(rig);
    colmap::Image image;
    image.SetName(names[i]);
    image.SetCameraId(camera.camera_id);
    const colmap::image_t image_id = database->WriteImage(image);
    image.SetImageId(image_id);
    colmap::Frame frame;
    frame.SetRigId(rig_id);
    frame.AddDataId(image.DataId());
    database->WriteFrame(frame);
    colmap::FeatureKeypoints feature_keypoints;
    feature_keypoints.reserve(keypoints[i].xy.size());
    for (const Eigen::Vector2d& xy : keypoints[i].xy) {
      feature_keypoints.emplace_back(xy.x(), xy.y());
    }
    database->WriteKeypoints(image_id, feature_keypoints);
  }
  // Each chunk's geometries estimated side by side (each pair seeds its
  // own RANSAC), then written in order.
  constexpr size_t kChunk = 4096;
  colmap::ThreadPool pool(options.num_threads);
  std::vector<colmap::TwoViewGeometry> geometries;
  for (size_t begin = 0; begin < pairs.size(); begin += kChunk) {
    const size_t end = std::min(pairs.size(), begin + kChunk);
    geometries.assign(end - begin, colmap::TwoViewGeometry());
    std::vector<std::shared_future<void>> verified;
    for (size_t p = begin; p < end; ++p) {
      verified.push_back(pool.AddTask([&, p] {
        geometries[p - begin] =
            VerifiedGeometry(pairs[p], cameras, keypoints, options.seed);
      }));
    }
    WaitForAll(verified);
    for (size_t p = begin; p < end; ++p) {
      const ImagePairMatches& pair = pairs[p];
      const int n1 = keypoints[pair.image1].xy.size();
      const int n2 = keypoints[pair.image2].xy.size();
      database->WriteMatches(pair.image1 + 1, pair.image2 + 1,
                             RawMatches(pair, n1, n2, options));
      database->WriteTwoViewGeometry(pair.image1 + 1, pair.image2 + 1,
                                     geometries[p - begin]);
    }
  }
}

}  // namespace

bool WriteSyntheticScene(const SyntheticSceneOptions& options,
                         const std::string& database_path,
                         const std::string& model_path,
                         SyntheticSceneSummary* summary, std::string* error) {
  if (!options.Check(error)) return false;
  if (fs::exists(database_path)) {
    *error = "database '" + database_path + "' already exists";
    return false;
  }
  std::error_code ec;
  const fs::path parent = fs::path(database_path).parent_path();
  if (!parent.empty()) fs::create_directories(parent, ec);
  if (!model_path.empty()) fs::create_directories(model_path, ec);
  if (ec) {
    *error = "cannot create output folders: " + ec.message();
    return false;
  }

  std::mt19937_64 rng(options.seed);
  const synthetic::SceneLayout layout =
      synthetic::BuildSceneLayout(options, rng);
  const auto points = synthetic::SampleScenePoints(
      layout.boxes, options.point_density, options.facade_relief, rng);
  const int num_images = static_cast<int>(layout.cameras.size());
  if (num_images < 2) {
    *error = "the options give fewer than two cameras";
    return false;
  }
  std::vector<ImageIntrinsics> intrinsics(num_images);
  std::vector<double> prior_focal(num_images);
  std::vector<std::string> names(num_images);
  std::uniform_real_distribution<double> focal(options.min_focal_px,
                                               options.max_focal_px);
  std::normal_distribution<double> prior_noise(0.0, options.focal_prior_error);
  for (int i = 0; i < num_images; ++i) {
    intrinsics[i] = {focal(rng), options.image_width, options.image_height};
    prior_focal[i] = intrinsics[i].focal_px * (1.0 + prior_noise(rng));
    names[i] = ImageName(layout.cameras[i].part, i);
  }
  const auto keypoints =
      synthetic::DetectKeypoints(layout, points, intrinsics, options);
  const auto pairs =
      synthetic::MatchKeypoints(layout, points, keypoints, options);

  WriteDatabase(database_path, options, intrinsics, prior_focal, names,
                keypoints, pairs);

  const colmap::Reconstruction gt =
      GroundTruth(layout, points, intrinsics, keypoints, pairs, names);
  if (!model_path.empty()) gt.WriteBinary(model_path);
  if (summary) {
    *summary = SyntheticSceneSummary();
    summary->num_images = num_images;
    summary->num_points3D = static_cast<int>(gt.NumPoints3D());
    for (const ImagePairMatches& pair : pairs) {
      ++(pair.is_false ? summary->num_false_pairs
                       : summary->num_verified_pairs);
    }
    double total_keypoints = 0;
    for (const ImageKeypoints& k : keypoints) total_keypoints += k.xy.size();
    summary->mean_keypoints_per_image = total_keypoints / num_images;
    summary->mean_track_length = gt.ComputeMeanTrackLength();
  }
  return true;
}

}  // namespace tmr
