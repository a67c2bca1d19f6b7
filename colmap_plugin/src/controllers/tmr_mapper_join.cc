// Copyright (c) 2026, the tmr authors. BSD-3-Clause.
// TmrMapperStages' join of the merge stage by parts (docs/distributed.md):
// light copies of the groups' models on their seams (MakeSeamModel), the
// models of each linked pair of groups (and of a group its merge left in
// several) aligned on their seam's correspondences, side by side within
// the budget, one similarity averaging, each scene's poses adjusted on the
// groups' longest tracks (JoinAdjustment), then each scene written piece by
// piece (ModelWriter), so that no step holds every group's models or
// seams.
#include <algorithm>
#include <chrono>
#include <filesystem>
#include <future>
#include <iterator>
#include <memory>
#include <unordered_set>

#include <colmap/util/threading.h>

#include "controllers/memory_budget.h"
#include "controllers/task_graph.h"
#include "controllers/tmr_mapper_options.h"
#include "controllers/tmr_mapper_stages.h"
#include "io/model_writer.h"
#include "io/task_database.h"
#include "merge/join_adjustment.h"
#include "merge/scene_assembly.h"
#include "sfm/model_edits.h"
#include "tmr/util/futures.h"
#include "tmr/util/process.h"

namespace tmr {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

}  // namespace

// One model of a group, as the join numbers it.
struct TmrMapperStages::JoinEntry {
  int group = 0;
  int index = 0;     // its number in its group's folder
  std::string path;  // the whole model
  JoinModel model;
  CompactTrackModel tracks;  // for the join's adjustment
};

// One alignment job of the join: group g's own models on all its seams
// (h < 0), or those of linked groups g < h on their link's seam.
struct TmrMapperStages::JoinJob {
  int g = 0;
  int h = -1;
  std::vector<int> images;  // the seam's (tree indices)
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
  std::vector<JoinJob> jobs;
  for (const auto& [g, h] : LinkedGroupPairs())
    jobs.push_back({g, h, LinkSeamImages(g, h)});
  const size_t num_links = jobs.size();
  // Light copies of every group's models, one group's models at a time:
  // on each link's seam, and on all the group's seams when its merge left
  // several models (whose alignment is then a job of its own).
  std::vector<JoinEntry> entries;
  const int points_per_image = JoinPointsPerImage();
  colmap::ThreadPool pool(std::max(1, num_threads));  // a model's copies
  for (int g = 0; g < static_cast<int>(groups_.size()); ++g) {
    if (!GroupMerged(g)) {
      return Fail("group " + std::to_string(g) +
                      " of the merge stage has not been merged",
                  error);
    }
    std::error_code ec;
    fs::remove_all(work_.GroupSeamModels(g), ec);
    int num_models = 0;
    while (fs::is_directory(fs::path(work_.GroupModels(g)) /
                            std::to_string(num_models)))
      ++num_models;
    std::vector<std::pair<int, std::unordered_set<colmap::image_t>>> copies;
    if (num_models > 1) {
      copies.emplace_back(-1, seams);
      jobs.push_back({g, -1, GroupSeamImages(g)});
    }
    for (size_t j = 0; j < num_links; ++j) {
      if (jobs[j].g != g && jobs[j].h != g) continue;
      const std::vector<uint32_t> ids = ImageIdsOf(tree_, jobs[j].images);
      copies.emplace_back(
          jobs[j].g == g ? jobs[j].h : jobs[j].g,
          std::unordered_set<colmap::image_t>(ids.begin(), ids.end()));
    }
    for (int m = 0; m < num_models; ++m) {
      const fs::path path = fs::path(work_.GroupModels(g)) / std::to_string(m);
      colmap::Reconstruction model;
      model.ReadBinary(path.string());
      JoinEntry entry{g, m, path.string(), {}, {}};
      std::vector<std::shared_future<void>> written;
      if (points_per_image > 0) {
        written.push_back(pool.AddTask([&] {
          entry.tracks = MakeCompactTrackModel(model, points_per_image);
        }));
      }
      for (const auto& copy : copies) {
        written.push_back(pool.AddTask([&, m] {
          colmap::Reconstruction light;
          MakeSeamModel(model, copy.second, &light);
          const std::string light_path = work_.GroupLightCopy(g, copy.first, m);
          std::error_code created;
          fs::create_directories(light_path, created);
          light.WriteBinary(light_path);
        }));
      }
      WaitForAll(written);  // they use `model` and `entry`
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
  if (!RunJoinJobs(jobs, entries, num_threads, record, progress, &aligned,
                   error))
    return false;
  std::vector<JoinModel> models;
  for (const JoinEntry& entry : entries) models.push_back(entry.model);
  std::vector<JoinedScene> joined;
  std::vector<TmrWeakLink> weak_links;
  {
    // Placing reads no correspondences: no cache, no database.
    const SceneAssembler placer(AssemblyOptions(o_, num_threads),
                                std::make_shared<colmap::DatabaseCache>(),
                                /*merge_database=*/"", tree_.image_names,
                                record);
    joined = placer.PlaceJoin(models, std::move(aligned), &weak_links);
  }
  // A scene of several pieces is adjusted; compact models only for those.
  const auto adjusts = [&](const JoinedScene& scene) {
    return points_per_image > 0 && scene.pieces.size() > 1;
  };
  std::vector<bool> adjusted_piece(entries.size(), false);
  for (const JoinedScene& scene : joined) {
    if (!adjusts(scene)) continue;
    for (const JoinPiece& piece : scene.pieces)
      adjusted_piece[piece.model] = true;
  }
  for (size_t e = 0; e < entries.size(); ++e)
    if (!adjusted_piece[e]) entries[e].tracks = {};
  ReleaseFreedMemory();
  // Each scene made again from the whole models, one at a time.
  const auto write_start = Clock::now();
  double adjust_seconds = 0;  // of the scenes' adjustments, between writes
  int num_registered = 0;
  for (size_t s = 0; s < joined.size(); ++s) {
    JoinAdjustment adjustment;
    const bool adjusted = adjusts(joined[s]);
    if (adjusted) {
      const auto adjust_start = Clock::now();
      for (const JoinPiece& piece : joined[s].pieces) {
        adjustment.AddPiece(entries.at(piece.model).tracks,
                            piece.scene_from_model, piece.dropped_images);
        entries.at(piece.model).tracks = {};
      }
      if (progress) {
        progress("join: adjusting model " + std::to_string(s) + " (" +
                 std::to_string(joined[s].num_images) + " images) on " +
                 std::to_string(points_per_image) +
                 " longest tracks per image");
      }
      const std::string report = adjustment.Adjust(
          ColmapOptions(o_, num_threads).GlobalBundleAdjustment());
      const int num_images = static_cast<int>(joined[s].num_images);
      record(
          {"join: adjust model " + std::to_string(s) + " on " +
               std::to_string(points_per_image) + " longest tracks per image",
           num_images, num_images, SecondsSince(adjust_start), true, report});
      adjust_seconds += SecondsSince(adjust_start);
      ReleaseFreedMemory();
    }
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
      if (adjusted) adjustment.MoveToAdjustedPoses(&model, num_threads);
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
          n, num_registered, SecondsSince(write_start) - adjust_seconds, true,
          ""});
  for (int g = 0; g < static_cast<int>(groups_.size()); ++g) {
    std::error_code ec;
    fs::remove_all(work_.GroupSeamModels(g), ec);
  }
  FinishScenes(joined.size(), std::move(weak_links), progress, report);
  return true;
}

int TmrMapperStages::JoinPointsPerImage() const {
  if (!o_.merge.adjust_join) return 0;
  return JoinTracksThatFit(o_.refinement.points_per_image, budget_.mib,
                           static_cast<int64_t>(tree_.image_ids.size()),
                           LargestGroupImages());
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

bool TmrMapperStages::RunJoinJobs(const std::vector<JoinJob>& jobs,
                                  const std::vector<JoinEntry>& entries,
                                  int num_threads, const Record& record,
                                  const Progress& progress,
                                  std::vector<ModelPairAlignment>* aligned,
                                  std::string* error) const {
  // An older plan without the join's expected memory: one job at a time.
  const double job_mib =
      JoinJobMiB(MergeMemoryMiB() > 0 ? MergeMemoryMiB() : budget_.mib);
  const double budget_mib = std::max(1.0, budget_.mib - ProcessMiB());
  const int side_by_side = std::max(
      1, std::min(num_threads, static_cast<int>(budget_mib / job_mib)));
  if (progress) {
    progress("join: " + std::to_string(jobs.size()) +
             " alignment jobs, up to " + std::to_string(side_by_side) +
             " at a time (each expected to need up to " + GiBText(job_mib) +
             ")");
  }
  std::vector<std::vector<ModelPairAlignment>> results(jobs.size());
  std::vector<std::string> errors(jobs.size());
  TaskGraph graph;
  for (size_t j = 0; j < jobs.size(); ++j) {
    TaskGraph::Task task;
    task.name = "join job " + std::to_string(j);
    task.cost = static_cast<double>(jobs[j].images.size());
    task.run = [&, j](int threads) {
      if (!AlignJoinJob(jobs[j], static_cast<int>(j), entries, threads, record,
                        &results[j], &errors[j]) &&
          errors[j].empty())
        errors[j] = "join job " + std::to_string(j) + " failed";
      ReleaseFreedMemory();
    };
    graph.Add(std::move(task));
  }
  graph.Run(side_by_side);
  for (size_t j = 0; j < jobs.size(); ++j) {
    if (!errors[j].empty()) return Fail(errors[j], error);
    aligned->insert(aligned->end(), std::make_move_iterator(results[j].begin()),
                    std::make_move_iterator(results[j].end()));
  }
  return true;
}

bool TmrMapperStages::AlignJoinJob(const JoinJob& job, int number,
                                   const std::vector<JoinEntry>& entries,
                                   int num_threads, const Record& record,
                                   std::vector<ModelPairAlignment>* aligned,
                                   std::string* error) const {
  const auto start = Clock::now();
  const int g = job.g, h = job.h;
  const std::vector<int>& images = job.images;
  if (images.size() < 2) return true;
  const std::string database = work_.JoinDatabase(number);
  const auto cache = LoadTaskDatabaseCache(
      o_.database_path, ImageIdsOf(tree_, images), database,
      o_.mapper.min_num_matches, o_.mapper.ignore_watermarks, error);
  std::error_code ec;
  fs::remove(database, ec);  // held in memory from here
  if (!cache) return false;
  // The light copies of the job's models, in the join's numbering (so that
  // each pair keeps model1 < model2).
  std::vector<int> number_of, group_of;
  std::vector<std::unique_ptr<colmap::Reconstruction>> light;
  std::vector<const colmap::Reconstruction*> models;
  for (int e = 0; e < static_cast<int>(entries.size()); ++e) {
    const int group = entries[e].group;
    if (group != g && group != h) continue;
    number_of.push_back(e);
    group_of.push_back(group);
    light.push_back(std::make_unique<colmap::Reconstruction>());
    const int other = h < 0 ? -1 : (group == g ? h : g);
    light.back()->ReadBinary(
        work_.GroupLightCopy(group, other, entries[e].index));
    models.push_back(light.back().get());
  }
  const SceneAssembler assembler(AssemblyOptions(o_, num_threads), cache,
                                 database, tree_.image_names, record);
  *aligned = assembler.AlignModelPairs(
      models, /*images_first=*/true,
      [&](int a, int b) { return h < 0 || group_of[a] != group_of[b]; });
  for (ModelPairAlignment& pair : *aligned) {
    pair.model1 = number_of[pair.model1];
    pair.model2 = number_of[pair.model2];
    if (pair.link) {
      pair.link->model1 = pair.model1;
      pair.link->model2 = pair.model2;
    }
  }
  record({"join: align " + (h < 0 ? "the models of group " + std::to_string(g)
                                  : "groups " + std::to_string(g) + " and " +
                                        std::to_string(h)),
          static_cast<int>(images.size()), 0, SecondsSince(start), true,
          std::to_string(aligned->size()) + " linked pairs of models, on " +
              std::to_string(images.size()) + " seam images"});
  return true;
}

}  // namespace tmr
