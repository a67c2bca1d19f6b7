// Copyright (c) 2026, the tmr authors. BSD-3-Clause.
// A tmr_synth scene for a test suite's fixture.
#pragma once

#include <colmap/estimators/two_view_geometry.h>
#include <colmap/scene/database.h>
#include <colmap/scene/database_cache.h>
#include <colmap/scene/reconstruction.h>
#include <unistd.h>

#include <filesystem>
#include <memory>
#include <string>
#include <unordered_set>

#include "sfm/model_edits.h"
#include "tmr/colmap/synthetic_scene.h"

namespace tmr {

// A tmr_synth city of two blocks side by side.
inline SyntheticSceneOptions TwoBlockCity() {
  SyntheticSceneOptions options;
  options.family = "city";
  options.city_blocks_x = 2;
  options.city_blocks_y = 1;
  return options;
}

// Writes the scene to a fresh folder named after `suite` and this process
// (ctest runs the test cases of a suite as parallel processes: one folder
// each): FOLDER/database.db and the ground truth in FOLDER/gt. Returns the
// folder, or an empty path with the reason in `error`.
inline std::filesystem::path WriteTestScene(
    const std::string& suite, const SyntheticSceneOptions& options,
    std::string* error) {
  namespace fs = std::filesystem;
  const fs::path dir = fs::temp_directory_path() /
                       ("tmr_" + suite + "_" + std::to_string(getpid()));
  fs::remove_all(dir);
  if (!WriteSyntheticScene(options, (dir / "database.db").string(),
                           (dir / "gt").string(), nullptr, error)) {
    return {};
  }
  return dir;
}

// Verifies every pair's matches of a test database again with COLMAP's
// two-view geometry (its defaults, as `colmap geometric_verifier` and the
// matchers do): the inlier matches and F, E, H a user's database holds,
// where tmr_synth writes its own inliers and no matrices.
inline void VerifyAgainWithColmap(const std::filesystem::path& database) {
  const std::shared_ptr<colmap::Database> db =
      colmap::Database::Open(database.string());
  const colmap::TwoViewGeometryOptions options;
  const auto all_matches = db->ReadAllMatches();
  db->ClearTwoViewGeometries();
  auto points = [&](colmap::image_t id) {
    std::vector<Eigen::Vector2d> xy;
    for (const colmap::FeatureKeypoint& k : db->ReadKeypoints(id))
      xy.emplace_back(k.x, k.y);
    return xy;
  };
  for (const auto& [pair_id, matches] : all_matches) {
    const auto [id1, id2] = colmap::PairIdToImagePair(pair_id);
    const colmap::Camera camera1 =
        db->ReadCamera(db->ReadImage(id1).CameraId());
    const colmap::Camera camera2 =
        db->ReadCamera(db->ReadImage(id2).CameraId());
    db->WriteTwoViewGeometry(
        id1, id2,
        colmap::EstimateTwoViewGeometry(camera1, points(id1), camera2,
                                        points(id2), matches, options));
  }
}

// COLMAP's correspondences of a test database, loaded as COLMAP's mapper
// loads them (pairs of at least 15 verified matches).
inline std::shared_ptr<colmap::DatabaseCache> LoadTestCache(
    const std::filesystem::path& database) {
  colmap::DatabaseCache::Options options;
  options.min_num_matches = 15;
  return colmap::DatabaseCache::Create(
      *colmap::Database::Open(database.string()), options);
}

// What a mapper that placed a group of photos badly leaves: the images in
// `group` moved by `moved` as one rigid block, every track split into the
// group's part (moved with them) and the rest's (kept), each kept when it
// still has two images.
inline void MoveGroupApart(const std::unordered_set<colmap::image_t>& group,
                           const colmap::Rigid3d& moved,
                           colmap::Reconstruction* model) {
  for (const colmap::point3D_t id : model->Point3DIds()) {
    const colmap::Point3D point = model->Point3D(id);
    colmap::Track in_rest, in_group;
    for (const auto& el : point.track.Elements())
      (group.count(el.image_id) ? in_group : in_rest).AddElement(el);
    model->DeletePoint3D(id);
    if (in_rest.Length() >= 2) model->AddPoint3D(point.xyz, in_rest);
    if (in_group.Length() >= 2) model->AddPoint3D(moved * point.xyz, in_group);
  }
  for (const colmap::image_t id : group) {
    SetPoseAndRegister(
        id, model->Image(id).CamFromWorld() * colmap::Inverse(moved), model);
  }
}

}  // namespace tmr
