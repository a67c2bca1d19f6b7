// Copyright (c) 2026, the tmr authors. BSD-3-Clause.
#include "controllers/tmr_mapper_stages.h"

#include <colmap/scene/reconstruction.h>
#include <glog/logging.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <iostream>
#include <string>

#include "tmr/colmap/synthetic_scene.h"

namespace tmr {
namespace {

namespace fs = std::filesystem;

bool Registers(const std::string& model_path, uint32_t image_id) {
  colmap::Reconstruction model;
  model.ReadBinary(model_path);
  return model.ExistsImage(image_id) && model.Image(image_id).HasPose();
}

// A fresh folder `name` (per process) holding database.db and gt of
// `num_places` overlapping plazas of 40 photos.
fs::path WritePlazas(const std::string& name, int num_places) {
  const fs::path dir =
      fs::temp_directory_path() / (name + "_" + std::to_string(getpid()));
  fs::remove_all(dir);
  FLAGS_minloglevel = google::GLOG_WARNING;  // COLMAP's log of every step
  SyntheticSceneOptions scene;
  scene.family = "plazas";
  scene.num_places = num_places;
  scene.cameras_per_place = 40;
  scene.num_unlinked_places = 0;
  std::string error;
  EXPECT_TRUE(WriteSyntheticScene(scene, (dir / "database.db").string(),
                                  (dir / "gt").string(), nullptr, &error))
      << error;
  return dir;
}

// Two overlapping plazas: each image cluster's leaf tasks register its
// halo (images of the other cluster), and the other cluster's own tasks
// register those images too, so the two cluster models share cameras.
TEST(TmrMapperStages, AHaloIsRegisteredByBothClustersTasks) {
  const fs::path dir = WritePlazas("tmr_halo", 2);
  ASSERT_TRUE(fs::exists(dir / "database.db"));
  std::string error;
  TmrMapperOptions options;
  options.database_path = (dir / "database.db").string();
  options.output_path = (dir / "out").string();
  options.num_threads = 1;
  TmrMapperStages stages(options);
  TmrMapperReport report;
  ASSERT_TRUE(stages.Plan(&report, /*one_process=*/false, nullptr, &error))
      << error;
  const TmrTree& tree = stages.tree();
  ASSERT_GE(tree.kernels.size(), 2u);
  for (const TmrMapperTask& task : stages.Tasks()) {  // kernels first
    TmrTaskReport row;
    ASSERT_TRUE(stages.RunTask(task, 1, &row, &error)) << error;
  }
  // The tasks of each image's own cluster, and where it is a halo image.
  int num_halo = 0, num_in_both = 0;
  for (int k = 0; k < static_cast<int>(tree.kernels.size()); ++k) {
    const TmrKernelNode& node = tree.kernels[k];
    for (size_t l = 0; l < node.leaf_halos.size(); ++l) {
      for (const int v : node.leaf_halos[l]) {
        ++num_halo;
        const uint32_t id = tree.image_ids[v];
        const bool in_halo_task = Registers(stages.work().LeafModel(k, l), id);
        bool in_own_task = false;
        for (int o = 0; o < static_cast<int>(tree.kernels.size()); ++o) {
          const TmrKernelNode& own = tree.kernels[o];
          if (o == k || !std::binary_search(own.cluster_images.begin(),
                                            own.cluster_images.end(), v))
            continue;
          in_own_task = Registers(stages.work().KernelModel(o), id);
          for (size_t m = 0; m < own.leaf_clusters.size(); ++m)
            in_own_task |= Registers(stages.work().LeafModel(o, m), id);
        }
        num_in_both += in_halo_task && in_own_task;
      }
    }
  }
  std::cout << num_in_both << " of " << num_halo
            << " halo images registered by both clusters' tasks\n";
  EXPECT_GT(num_halo, 0);
  // Most halo images see enough of the neighbouring cluster to register.
  EXPECT_GE(2 * num_in_both, num_halo)
      << num_in_both << " of " << num_halo << " halo images in both";
  fs::remove_all(dir);
}

// A cap on a group's photos splits a merge stage that fits the budget,
// into groups of at most that many photos of clusters and halos; without
// it, the same plan has no groups.
TEST(TmrMapperStages, MaxGroupImagesSplitsAMergeThatFitsTheBudget) {
  const fs::path dir = WritePlazas("tmr_group_cap", 4);
  ASSERT_TRUE(fs::exists(dir / "database.db"));
  std::string error;
  for (const int max_images : {0, 90}) {
    TmrMapperOptions options;
    options.database_path = (dir / "database.db").string();
    options.output_path = (dir / ("out" + std::to_string(max_images))).string();
    options.num_threads = 1;
    options.memory_budget = 8.0;  // the whole merge fits
    options.merge.max_group_images = max_images;
    TmrMapperStages stages(options);
    TmrMapperReport report;
    ASSERT_TRUE(stages.Plan(&report, /*one_process=*/false, nullptr, &error))
        << error;
    ASSERT_LT(stages.MergeMemoryMiB(), 8.0 * 1024);
    const auto& groups = stages.cluster_groups();
    if (max_images == 0) {
      EXPECT_TRUE(groups.empty());
      continue;
    }
    ASSERT_GE(groups.size(), 2u);
    size_t num_kernels = 0;
    for (const auto& group : groups) {
      num_kernels += group.kernels.size();
      if (group.kernels.size() > 1) {
        EXPECT_LE(
            group.num_images - static_cast<int>(group.extra_images.size()),
            max_images);
      }
    }
    EXPECT_EQ(num_kernels, stages.tree().kernels.size());
  }
  fs::remove_all(dir);
}

}  // namespace
}  // namespace tmr
