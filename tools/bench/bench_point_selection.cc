// Copyright (c) 2026, the tmr authors. BSD-3-Clause.
// bench_point_selection DATABASE MODEL GROUND_TRUTH [TURN_DEG]
// Which points a global bundle adjustment of a merged model needs: tmr's
// longest tracks per image (AdjustOnLongestTracks, --Tmr.
// merge_refine_points_per_image 500, used while scenes merge) against
// COLMAP 4.1's redundant-point pruning (Mapper.
// ba_global_ignore_redundant_points3D: FindRedundantPoints3D, the adjustment
// on the rest, then the pruned points with everything else held), and
// both against adjusting every point (tmr's AdjustWholeModel and COLMAP's
// AdjustGlobalBundle). Each starts from MODEL with the half of its
// cameras east of the median turned by TURN_DEG (default 0.5) about their
// centroid, as a merge that fits one side leaves the other, with tracks
// re-linked as RefineMergedModel does; one adjustment each, then scored
// against GROUND_TRUTH. The database and models are only read.
#include <colmap/scene/reconstruction_pruning.h>
#include <colmap/sfm/incremental_mapper.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <functional>
#include <iostream>
#include <optional>
#include <string>

#include "evaluation/evaluate_reconstruction.h"
#include "io/task_database.h"
#include "merge/merged_model_refinement.h"
#include "sfm/model_edits.h"
#include "tmr/colmap/tmr_mapper.h"

namespace {

// The cameras east of the median camera centre, turned about their
// centroid by `degrees` around the vertical axis.
void TurnEasternHalf(double degrees, colmap::Reconstruction* model) {
  std::vector<colmap::image_t> ids = model->RegImageIds();
  std::sort(ids.begin(), ids.end(), [&](colmap::image_t a, colmap::image_t b) {
    return model->Image(a).ProjectionCenter().x() <
           model->Image(b).ProjectionCenter().x();
  });
  const std::vector<colmap::image_t> east(ids.begin() + ids.size() / 2,
                                          ids.end());
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
  for (const colmap::image_t id : east)
    centroid += model->Image(id).ProjectionCenter();
  centroid /= static_cast<double>(east.size());
  const Eigen::Quaterniond turn(
      Eigen::AngleAxisd(degrees * M_PI / 180.0, Eigen::Vector3d::UnitZ()));
  const colmap::Rigid3d moved_from_world(turn, centroid - turn * centroid);
  for (const colmap::image_t id : east) {
    tmr::SetPoseAndRegister(
        id, model->Image(id).CamFromWorld() * colmap::Inverse(moved_from_world),
        model);
  }
}

// TURN_DEG of the command line (0.5 without it); nothing, after one error
// line, when it is not a number of degrees in (0, 90).
std::optional<double> TurnDegrees(int argc, char** argv) {
  if (argc < 5) return 0.5;
  char* end = nullptr;
  const double turn_deg = std::strtod(argv[4], &end);
  if (*argv[4] == '\0' || *end != '\0' || !(turn_deg > 0 && turn_deg < 90)) {
    std::cerr << "bench_point_selection: error: TURN_DEG must be a number "
                 "of degrees in (0, 90), not '"
              << argv[4] << "'\n";
    return std::nullopt;
  }
  return turn_deg;
}

// A task database of this run's own in the temporary folder.
std::string ScratchDatabasePath() {
  return (std::filesystem::temp_directory_path() /
          ("bench_point_selection_" + std::to_string(getpid()) + ".db"))
      .string();
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 4 && argc != 5) {
    std::cerr << "usage: bench_point_selection DATABASE MODEL GROUND_TRUTH "
                 "[TURN_DEG]\n";
    return 2;
  }
  const std::optional<double> turn = TurnDegrees(argc, argv);
  if (!turn) return 2;
  const double turn_deg = *turn;
  colmap::Reconstruction merged, truth;
  try {
    merged.Read(argv[2]);
    truth.Read(argv[3]);
  } catch (const std::exception& e) {
    std::cerr << "bench_point_selection: error: " << e.what() << "\n";
    return 1;
  }
  const std::vector<colmap::image_t> registered = merged.RegImageIds();
  const std::vector<uint32_t> ids(registered.begin(), registered.end());
  const std::string scratch = ScratchDatabasePath();
  std::string error;
  const auto cache =
      tmr::LoadTaskDatabaseCache(argv[1], ids, scratch, 15, false, &error);
  std::filesystem::remove(scratch);
  if (!cache) {
    std::cerr << "bench_point_selection: error: " << error << "\n";
    return 1;
  }
  colmap::IncrementalPipelineOptions options;
  options.num_threads = 2;
  const colmap::BundleAdjustmentOptions ba = options.GlobalBundleAdjustment();
  // tmr's adjustments as tmr_mapper runs them (AdjustMergedBundle): on the
  // longest tracks while scenes grow, and whole.
  tmr::MergedModelAdjustment longest_tracks;
  longest_tracks.longest_tracks_per_image =
      tmr::TmrMapperOptions().refinement.points_per_image;
  tmr::MergedModelAdjustment whole;
  whole.max_block_images = 0;

  using Adjust = std::function<std::string(colmap::IncrementalMapper*)>;
  const std::vector<std::pair<std::string, Adjust>> selections = {
      {"tmr: " + std::to_string(longest_tracks.longest_tracks_per_image) +
           " longest tracks per image",
       [&](colmap::IncrementalMapper* mapper) {
         return tmr::AdjustMergedBundle(options, longest_tracks, mapper);
       }},
      {"COLMAP: redundant points pruned (gain 0.05)",
       [&](colmap::IncrementalMapper* mapper) {
         const size_t pruned =
             colmap::FindRedundantPoints3D(
                 options.mapper
                     .ba_global_ignore_redundant_points3D_min_coverage_gain,
                 *mapper->Reconstruction())
                 .size();
         colmap::IncrementalMapper::Options pruning = options.Mapper();
         pruning.ba_global_ignore_redundant_points3D = true;
         mapper->AdjustGlobalBundle(pruning, ba);
         return "global on " +
                std::to_string(mapper->Reconstruction()->NumPoints3D() -
                               pruned) +
                " of " +
                std::to_string(mapper->Reconstruction()->NumPoints3D()) +
                " points, then the rest";
       }},
      {"tmr: every point (AdjustWholeModel)",
       [&](colmap::IncrementalMapper* mapper) {
         return tmr::AdjustMergedBundle(options, whole, mapper);
       }},
      {"COLMAP: every point (AdjustGlobalBundle)",
       [&](colmap::IncrementalMapper* mapper) {
         mapper->AdjustGlobalBundle(options.Mapper(), ba);
         return std::string("every point");
       }},
  };
  std::cout << "| selection | adjustment s | median rotation error (p90) | "
               "mean reprojection px | points |\n|---|---|---|---|---|\n";
  for (const auto& [name, adjust] : selections) {
    auto model = std::make_shared<colmap::Reconstruction>(merged);
    TurnEasternHalf(turn_deg, model.get());
    colmap::IncrementalMapper mapper(cache);
    mapper.BeginReconstruction(model);
    mapper.CompleteAndMergeTracks(options.Triangulation());
    mapper.Retriangulate(options.Triangulation());
    mapper.ObservationManager().FilterObservationsWithNegativeDepth();
    const auto start = std::chrono::steady_clock::now();
    const std::string report = adjust(&mapper);
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start)
            .count();
    mapper.EndReconstruction(/*discard=*/false);
    const tmr::ModelEvaluation e = tmr::EvaluateReconstruction(
        truth, *model, tmr::ModelEvaluationOptions());
    std::printf("| %s | %.1f | %.3f° (%.3f°) | %.3f | %s |\n", name.c_str(),
                seconds, e.rotation_error_deg.median, e.rotation_error_deg.p90,
                model->ComputeMeanReprojectionError(), report.c_str());
    std::fflush(stdout);
  }
  return 0;
}
