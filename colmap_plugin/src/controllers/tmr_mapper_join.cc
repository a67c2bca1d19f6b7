// Copyright (c) 2026, the tmr authors. BSD-3-Clause.
// TmrMapperStages' join of the merge stage by parts (docs/distributed.md):
// the groups' models placed on light copies of their seams (MakeSeamModel),
// then each scene written piece by piece (ModelWriter), so that no step
// holds every group's models.
#include <chrono>
#include <filesystem>
#include <unordered_set>

#include "controllers/tmr_mapper_options.h"
#include "controllers/tmr_mapper_stages.h"
#include "io/model_writer.h"
#include "io/task_database.h"
#include "merge/scene_assembly.h"
#include "sfm/model_edits.h"
#include "tmr/util/process.h"

namespace tmr {

namespace fs = std::filesystem;

bool TmrMapperStages::JoinGroups(int num_threads, const Record& record,
                                 const Progress& progress,
                                 TmrMapperReport* report,
                                 std::string* error) const {
  const auto start = std::chrono::steady_clock::now();
  // The seams: the images several groups hold, or that verified pairs link
  // across groups.
  const std::vector<uint32_t> seam_ids = ImageIdsOf(tree_, seam_images_);
  const std::unordered_set<colmap::image_t> seams(seam_ids.begin(),
                                                  seam_ids.end());
  std::vector<std::string> paths;  // every group's models
  std::vector<std::shared_ptr<colmap::Reconstruction>> light;
  for (int g = 0; g < static_cast<int>(groups_.size()); ++g) {
    if (!GroupMerged(g)) {
      return Fail("group " + std::to_string(g) +
                      " of the merge stage has not been merged",
                  error);
    }
    for (int m = 0;; ++m) {
      const fs::path path = fs::path(work_.GroupModels(g)) / std::to_string(m);
      if (!fs::is_directory(path)) break;
      paths.push_back(path.string());
      colmap::Reconstruction model;
      model.ReadBinary(path.string());
      light.push_back(std::make_shared<colmap::Reconstruction>());
      MakeSeamModel(model, seams, light.back().get());
    }
  }
  std::shared_ptr<const colmap::DatabaseCache> cache =
      std::make_shared<colmap::DatabaseCache>();
  if (seam_ids.size() > 1) {
    cache = LoadTaskDatabaseCache(
        o_.database_path, seam_ids, work_.JoinDatabase(),
        o_.mapper.min_num_matches, o_.mapper.ignore_watermarks, error);
    if (!cache) return false;
  }
  const int n = static_cast<int>(tree_.image_ids.size());
  record(
      {"join: load the seams of " + std::to_string(groups_.size()) + " groups",
       n, 0, SecondsSince(start), true,
       std::to_string(paths.size()) + " models, " +
           std::to_string(seam_ids.size()) +
           " images on the seams (in several groups, or matched across)"});
  std::vector<JoinedScene> joined;
  std::vector<TmrWeakLink> weak_links;
  {
    const SceneAssembler assembler(AssemblyOptions(o_, num_threads),
                                   std::move(cache), work_.JoinDatabase(),
                                   tree_.image_names, record);
    joined = assembler.Join(std::move(light));
    std::vector<std::shared_ptr<colmap::Reconstruction>> scenes;
    for (JoinedScene& scene : joined) scenes.push_back(std::move(scene.model));
    weak_links = assembler.WeakLinks(scenes);
  }
  ReleaseFreedMemory();
  // Each scene made again from the whole models, one at a time.
  const auto write_start = std::chrono::steady_clock::now();
  int num_registered = 0;
  for (size_t s = 0; s < joined.size(); ++s) {
    const std::string path =
        (fs::path(o_.output_path) / std::to_string(s)).string();
    ModelWriter writer(path);
    bool written = writer.Open();
    for (const JoinPiece& piece : joined[s].pieces) {
      if (!written) break;
      colmap::Reconstruction model;
      model.ReadBinary(paths.at(piece.model));
      for (const colmap::image_t id : piece.dropped_images)
        model.DeRegisterFrame(model.Image(id).FrameId());
      model.Transform(piece.scene_from_model);
      if (!o_.image_path.empty())
        model.ExtractColorsForAllImages(o_.image_path);
      written = writer.Append(&model);
    }
    if (!written || !writer.Finish())
      return Fail("cannot write model '" + path + "'", error);
    report->model_sizes.push_back(static_cast<int>(writer.NumRegImages()));
    num_registered += static_cast<int>(writer.NumRegImages());
  }
  record({"join: write " + std::to_string(joined.size()) +
              " models, one group's model at a time",
          n, num_registered, SecondsSince(write_start), true, ""});
  FinishScenes(joined.size(), std::move(weak_links), progress, report);
  return true;
}

}  // namespace tmr
