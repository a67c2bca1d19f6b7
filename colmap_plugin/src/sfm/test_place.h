// Copyright (c) 2026, the tmr authors. BSD-3-Clause.
// A test suite's fixture: one tmr_synth place of 30 photos and one that
// nothing links to, their ground truth and COLMAP's correspondences, from
// which the tests cut models (Keep, Images).
#pragma once

#include <colmap/geometry/sim3.h>
#include <colmap/scene/database_cache.h>
#include <colmap/scene/reconstruction.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "io/model_files.h"
#include "sfm/test_scene.h"

namespace tmr {

class PlaceModelsTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    // One place of 30 photos and one that nothing links to.
    SyntheticSceneOptions options;
    options.num_places = 1;
    options.num_unlinked_places = 1;
    options.cameras_per_place = 30;
    options.place_distance = 100;
    std::string error;
    dir_ = WriteTestScene("place_models_test", options, &error);
    ASSERT_FALSE(dir_.empty()) << error;
    gt_ = new colmap::Reconstruction(ReadModel((dir_ / "gt").string()));
    cache_ = new std::shared_ptr<colmap::DatabaseCache>(
        LoadTestCache(dir_ / "database.db"));
  }
  static void TearDownTestSuite() {
    delete gt_;
    gt_ = nullptr;
    delete cache_;
    cache_ = nullptr;
    std::filesystem::remove_all(dir_);
  }

  // The ground truth with only the given images registered.
  static colmap::Reconstruction Keep(
      const std::vector<colmap::image_t>& images) {
    colmap::Reconstruction model = *gt_;
    for (const colmap::image_t id : gt_->RegImageIds()) {
      if (std::find(images.begin(), images.end(), id) == images.end())
        model.DeRegisterFrame(model.Image(id).FrameId());
    }
    return model;
  }

  // Registered images of the ground truth whose name starts with `prefix`,
  // by id.
  static std::vector<colmap::image_t> Images(const std::string& prefix) {
    std::vector<colmap::image_t> ids;
    for (const colmap::image_t id : gt_->RegImageIds()) {
      if (gt_->Image(id).Name().rfind(prefix, 0) == 0) ids.push_back(id);
    }
    std::sort(ids.begin(), ids.end());
    return ids;
  }

  static inline std::filesystem::path dir_;
  static inline colmap::Reconstruction* gt_ = nullptr;
  static inline std::shared_ptr<colmap::DatabaseCache>* cache_ = nullptr;
};

// A similarity that moves a model far from where it was.
inline const colmap::Sim3d kMoved(2.5,
                           Eigen::Quaterniond(Eigen::AngleAxisd(
                               0.7,
                               Eigen::Vector3d(0.2, 1.0, -0.4).normalized())),
                           Eigen::Vector3d(14, -3, 8));

}  // namespace tmr
