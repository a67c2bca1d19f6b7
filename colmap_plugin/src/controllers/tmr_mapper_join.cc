// Copyright (c) 2026, the tmr authors. BSD-3-Clause.
// TmrMapperStages' join of the merge stage by parts (docs/distributed.md):
// light copies of the groups' models on their seams (MakeSeamModel), each
// linked pair of groups aligned on its own seams' correspondences, one
// similarity averaging, then each scene written piece by piece
// (ModelWriter), so that no step holds every group's models or seams.
#include <algorithm>
#include <chrono>
#include <filesystem>
#include <iterator>
#include <memory>
#include <unordered_set>

#include "controllers/tmr_mapper_options.h"
#include "controllers/tmr_mapper_stages.h"
#include "io/model_writer.h"
#include "io/task_database.h"
#include "merge/scene_assembly.h"
#include "sfm/model_edits.h"
#include "tmr/util/process.h"

namespace tmr {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

}  // namespace

// One model of a group, as the join numbers it.
struct TmrMapperStages::JoinEntry {
  int group = 0;
  std::string path;        // the whole model
  std::string seam_model;  // its light copy (MakeSeamModel)
  JoinModel model;
};

bool TmrMapperStages::JoinGroups(int num_threads, const Record& record,
                                 const Progress& progress,
                                 TmrMapperReport* report,
                                 std::string* error) const {
  const auto start = Clock::now();
  // The seams: the images several groups hold, or that verified pairs link
  // across groups.
  const std::vector<uint32_t> seam_ids = ImageIdsOf(tree_, seam_images_);
  const std::unordered_set<colmap::image_t> seams(seam_ids.begin(),
                                                  seam_ids.end());
  // Light copies of every group's models, one group's models at a time.
  std::vector<JoinEntry> entries;
  for (int g = 0; g < static_cast<int>(groups_.size()); ++g) {
    if (!GroupMerged(g)) {
      return Fail("group " + std::to_string(g) +
                      " of the merge stage has not been merged",
                  error);
    }
    const fs::path seam_folder(work_.GroupSeamModels(g));
    std::error_code ec;
    fs::remove_all(seam_folder, ec);
    for (int m = 0;; ++m) {
      const fs::path path = fs::path(work_.GroupModels(g)) / std::to_string(m);
      if (!fs::is_directory(path)) break;
      colmap::Reconstruction model;
      model.ReadBinary(path.string());
      colmap::Reconstruction light;
      MakeSeamModel(model, seams, &light);
      const fs::path light_path = seam_folder / std::to_string(m);
      fs::create_directories(light_path, ec);
      light.WriteBinary(light_path.string());
      JoinEntry entry{g, path.string(), light_path.string(), {}};
      entry.model.num_images = model.NumRegImages();
      for (const colmap::image_t id : model.RegImageIds()) {
        if (seams.count(id))
          entry.model.seam_image_points[id] = model.Image(id).NumPoints3D();
      }
      entries.push_back(std::move(entry));
    }
  }
  // Numbered largest first, as the assembly numbers models.
  std::stable_sort(entries.begin(), entries.end(),
                   [](const JoinEntry& a, const JoinEntry& b) {
                     return a.model.num_images > b.model.num_images;
                   });
  const int n = static_cast<int>(tree_.image_ids.size());
  record({"join: light copies of the models of " +
              std::to_string(groups_.size()) + " groups",
          n, 0, SecondsSince(start), true,
          std::to_string(entries.size()) + " models, " +
              std::to_string(seam_ids.size()) +
              " images on the seams (in several groups, or matched across)"});
  std::vector<ModelPairAlignment> aligned;
  // Each group's own models are linked too, in the first pair it is in.
  std::vector<bool> inner_aligned(groups_.size(), false);
  for (const auto& [g, h] : LinkedGroupPairs()) {
    const bool inner_g = !inner_aligned[g], inner_h = !inner_aligned[h];
    inner_aligned[g] = inner_aligned[h] = true;
    if (!AlignGroupPair(g, h, inner_g, inner_h, entries, num_threads, record,
                        &aligned, error))
      return false;
    ReleaseFreedMemory();
  }
  std::vector<JoinModel> models;
  for (const JoinEntry& entry : entries) models.push_back(entry.model);
  std::vector<JoinedScene> joined;
  std::vector<TmrWeakLink> weak_links;
  {
    const SceneAssembler placer(AssemblyOptions(o_, num_threads),
                                std::make_shared<colmap::DatabaseCache>(),
                                work_.JoinDatabase(), tree_.image_names,
                                record);
    joined = placer.PlaceJoin(models, std::move(aligned), &weak_links);
  }
  ReleaseFreedMemory();
  // Each scene made again from the whole models, one at a time.
  const auto write_start = Clock::now();
  int num_registered = 0;
  for (size_t s = 0; s < joined.size(); ++s) {
    const std::string path =
        (fs::path(o_.output_path) / std::to_string(s)).string();
    ModelWriter writer(path);
    bool written = writer.Open();
    for (const JoinPiece& piece : joined[s].pieces) {
      if (!written) break;
      colmap::Reconstruction model;
      model.ReadBinary(entries.at(piece.model).path);
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
  for (int g = 0; g < static_cast<int>(groups_.size()); ++g) {
    std::error_code ec;
    fs::remove_all(work_.GroupSeamModels(g), ec);
  }
  FinishScenes(joined.size(), std::move(weak_links), progress, report);
  return true;
}

std::vector<std::pair<int, int>> TmrMapperStages::LinkedGroupPairs() const {
  std::vector<std::pair<int, int>> pairs;
  for (int g = 0; g < static_cast<int>(groups_.size()); ++g)
    for (const int h : groups_[g].links) pairs.emplace_back(g, h);
  if (!pairs.empty()) return pairs;
  // A plan written before groups had links: every pair.
  for (int g = 0; g < static_cast<int>(groups_.size()); ++g)
    for (int h = g + 1; h < static_cast<int>(groups_.size()); ++h)
      pairs.emplace_back(g, h);
  return pairs;
}

bool TmrMapperStages::AlignGroupPair(int g, int h, bool inner_g, bool inner_h,
                                     const std::vector<JoinEntry>& entries,
                                     int num_threads, const Record& record,
                                     std::vector<ModelPairAlignment>* aligned,
                                     std::string* error) const {
  const auto start = Clock::now();
  const std::vector<int> images = PairSeamImages(g, h, inner_g, inner_h);
  if (images.size() < 2) return true;
  const auto cache = LoadTaskDatabaseCache(
      o_.database_path, ImageIdsOf(tree_, images), work_.JoinDatabase(),
      o_.mapper.min_num_matches, o_.mapper.ignore_watermarks, error);
  if (!cache) return false;
  // The two groups' light copies, in the join's numbering (so that each
  // pair keeps model1 < model2).
  std::vector<int> number, group_of;
  std::vector<std::unique_ptr<colmap::Reconstruction>> light;
  std::vector<const colmap::Reconstruction*> models;
  for (int e = 0; e < static_cast<int>(entries.size()); ++e) {
    if (entries[e].group != g && entries[e].group != h) continue;
    number.push_back(e);
    group_of.push_back(entries[e].group);
    light.push_back(std::make_unique<colmap::Reconstruction>());
    light.back()->ReadBinary(entries[e].seam_model);
    models.push_back(light.back().get());
  }
  const SceneAssembler assembler(AssemblyOptions(o_, num_threads), cache,
                                 work_.JoinDatabase(), tree_.image_names,
                                 record);
  std::vector<ModelPairAlignment> pairs = assembler.AlignModelPairs(
      models, /*images_first=*/true, [&](int a, int b) {
        if (group_of[a] != group_of[b]) return true;
        return group_of[a] == g ? inner_g : inner_h;
      });
  for (ModelPairAlignment& pair : pairs) {
    pair.model1 = number[pair.model1];
    pair.model2 = number[pair.model2];
    if (pair.link) {
      pair.link->model1 = pair.model1;
      pair.link->model2 = pair.model2;
    }
  }
  record(
      {"join: align groups " + std::to_string(g) + " and " + std::to_string(h),
       static_cast<int>(images.size()), 0, SecondsSince(start), true,
       std::to_string(pairs.size()) + " linked pairs of models, on " +
           std::to_string(images.size()) + " seam images"});
  aligned->insert(aligned->end(), std::make_move_iterator(pairs.begin()),
                  std::make_move_iterator(pairs.end()));
  return true;
}

}  // namespace tmr
