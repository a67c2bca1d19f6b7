// Copyright (c) 2026, the tmr authors. BSD-3-Clause.
// TmrMapperStages' merge stage by parts (docs/distributed.md): groups of
// image clusters that fit the memory budget (GroupClusters), each merged on
// its own correspondences, then joined by the images several groups hold
// (their seams: tmr_mapper_seams.cc).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <numeric>
#include <sstream>

#include "controllers/memory_budget.h"
#include "controllers/task_graph.h"
#include "controllers/tmr_mapper_options.h"
#include "controllers/tmr_mapper_stages.h"
#include "io/model_files.h"
#include "io/task_database.h"
#include "merge/scene_assembly.h"
#include "sfm/reconstruction_task.h"
#include "tmr/io/atomic_file.h"
#include "tmr/partition/merge_groups.h"
#include "tmr/util/option_table.h"
#include "tmr/util/process.h"

namespace tmr {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

std::string JoinNumbers(const std::vector<int>& values) {
  std::string text;
  for (const int v : values)
    text += (text.empty() ? "" : ",") + std::to_string(v);
  return text;
}

// "1,2,3" (or "").
std::vector<int> ReadNumbers(const std::string& text) {
  std::vector<int> numbers;
  std::istringstream values(text);
  for (std::string value; std::getline(values, value, ',');)
    numbers.push_back(std::stoi(value));
  return numbers;
}

// What identifies group g's result in the work folder: its clusters and
// extra images.
std::string GroupContent(const TmrMapperStages::ClusterGroup& group) {
  return "kernels=" + JoinNumbers(group.kernels) +
         " extra=" + JoinNumbers(group.extra_images);
}

}  // namespace

void TmrMapperStages::PlanGroups(const MatchGraph& graph, bool for_memory) {
  groups_.clear();
  const int n = graph.NumImages();
  const int max_images = o_.merge.max_group_images;
  const bool over_budget = for_memory && MergeMemoryMiB() > budget_.mib;
  if (!over_budget && (max_images <= 0 || n <= max_images)) return;
  // A group's clusters share their halos and one process: its peak is
  // that of its images together; one of more images than max_images fits
  // no budget (unless it is one cluster, a group alone).
  const auto group_cost = [&](const std::vector<int>& kernels) {
    const std::vector<int> images = GroupImages({kernels, {}, 0, 0.0, {}, {}});
    if (max_images > 0 && static_cast<int>(images.size()) > max_images)
      return std::numeric_limits<double>::infinity();
    return MergePeakMiB(LoadOfImages(graph, images),
                        o_.refinement.points_per_image,
                        o_.refinement.max_block_images);
  };
  std::vector<int> cluster_of(n, -1);
  std::vector<double> cost;
  for (int k = 0; k < static_cast<int>(tree_.kernels.size()); ++k) {
    const TmrKernelNode& node = tree_.kernels[k];
    for (const int i : node.cluster_images) cluster_of[i] = k;
    cost.push_back(group_cost({k}));
  }
  const std::vector<std::vector<int>> grouped = GroupClusters(
      cost, LinkClusters(graph, cluster_of), budget_.mib, group_cost);
  if (grouped.size() < 2) return;  // one group is the whole merge stage
  std::vector<int> group_of_kernel(tree_.kernels.size());
  for (int g = 0; g < static_cast<int>(grouped.size()); ++g) {
    groups_.push_back({grouped[g], {}, 0, 0.0, {}, {}});
    for (const int k : grouped[g]) group_of_kernel[k] = g;
  }
  // The images of no group's clusters or halos (unclustered) go to the
  // group their verified matches link them to most; group 0 when none.
  std::vector<bool> held(n, false);
  for (const ClusterGroup& group : groups_)
    for (const int i : GroupImages(group)) held[i] = true;
  std::vector<std::map<int, int64_t>> matches_into(n);
  for (const MatchGraphPair& pair : graph.pairs) {
    for (const auto& [a, b] : {std::pair(pair.image1, pair.image2),
                               std::pair(pair.image2, pair.image1)}) {
      if (!held[a] && cluster_of[b] >= 0)
        matches_into[a][group_of_kernel[cluster_of[b]]] += pair.num_inliers;
    }
  }
  for (int i = 0; i < n; ++i) {
    if (held[i]) continue;
    int best = 0;
    int64_t most = 0;
    for (const auto& [g, count] : matches_into[i]) {
      if (count > most) {
        best = g;
        most = count;
      }
    }
    groups_[best].extra_images.push_back(i);
  }
  MemoryLoad largest;  // the join writes one group's models at a time
  for (int g = 0; g < static_cast<int>(groups_.size()); ++g) {
    ClusterGroup& group = groups_[g];
    const std::vector<int> images = GroupImages(group);
    const MemoryLoad load = LoadOfImages(graph, images);
    group.num_images = static_cast<int>(images.size());
    group.memory_mib = MergePeakMiB(load, o_.refinement.points_per_image,
                                    o_.refinement.max_block_images);
    memory_mib_["merge." + std::to_string(g)] = group.memory_mib;
    if (load.matched_keypoints > largest.matched_keypoints) largest = load;
  }
  seam_images_ = SeamImages(graph);
  LinkGroups(graph);
  // The join's alignment jobs: a group's own models on all its seams (when
  // its merge leaves several), two linked groups' on their link's seam.
  MemoryLoad largest_job;
  const auto job = [&](const std::vector<int>& images) {
    const MemoryLoad load = LoadOfImages(graph, images);
    if (load.matched_keypoints > largest_job.matched_keypoints)
      largest_job = load;
  };
  for (int g = 0; g < static_cast<int>(groups_.size()); ++g) {
    job(GroupSeamImages(g));
    for (const int h : groups_[g].links) job(LinkSeamImages(g, h));
  }
  memory_mib_["merge"] = JoinPeakMiB(
      largest, largest_job,
      JoinAdjustmentMiB(n, JoinPointsPerImage(), LargestGroupImages()));
}

std::vector<int> TmrMapperStages::GroupImages(const ClusterGroup& group) const {
  std::vector<int> images = group.extra_images;
  for (const int k : group.kernels) {
    const TmrKernelNode& node = tree_.kernels.at(k);
    images.insert(images.end(), node.cluster_images.begin(),
                  node.cluster_images.end());
    for (const auto& halo : node.leaf_halos)
      images.insert(images.end(), halo.begin(), halo.end());
  }
  std::sort(images.begin(), images.end());
  images.erase(std::unique(images.begin(), images.end()), images.end());
  return images;
}

std::string TmrMapperStages::GroupPlanLines() const {
  std::string lines;
  for (int g = 0; g < static_cast<int>(groups_.size()); ++g) {
    const ClusterGroup& group = groups_[g];
    lines += "merge." + std::to_string(g) + " " +
             std::to_string(group.num_images) + " 0 " +
             std::to_string(std::lround(group.memory_mib)) + " " +
             GroupContent(group) + " links=" + JoinNumbers(group.links) + "\n";
  }
  if (!groups_.empty()) {
    lines += "seams " + std::to_string(seam_images_.size()) + " 0 0 " +
             JoinNumbers(seam_images_) + "\n";
  }
  for (int g = 0; g < static_cast<int>(groups_.size()); ++g) {
    const ClusterGroup& group = groups_[g];
    for (size_t l = 0; l < group.link_seams.size(); ++l) {
      lines += "seam." + std::to_string(g) + "." +
               std::to_string(group.links[l]) + " " +
               std::to_string(group.link_seams[l].size()) + " 0 0 " +
               JoinNumbers(group.link_seams[l]) + "\n";
    }
  }
  return lines;
}

bool TmrMapperStages::ReadGroupPlanLine(const std::string& id, int images,
                                        double mib, std::istringstream* rest) {
  std::string list;  // "name=1,2,..." fields
  if (id == "seams") {
    *rest >> list;
    seam_images_ = ReadNumbers(list);
    return true;
  }
  if (id.rfind("seam.", 0) == 0) {  // seam.G.H: the seam of G's link to H
    const size_t dot = id.find('.', 5);
    if (dot == std::string::npos) throw std::invalid_argument(id);
    ClusterGroup& group = groups_.at(std::stoi(id.substr(5, dot - 5)));
    const auto l = std::find(group.links.begin(), group.links.end(),
                             std::stoi(id.substr(dot + 1)));
    if (l == group.links.end()) throw std::invalid_argument("no link " + id);
    group.link_seams.resize(group.links.size());
    *rest >> list;
    group.link_seams[l - group.links.begin()] = ReadNumbers(list);
    return true;
  }
  if (id.rfind("merge.", 0) != 0) return false;
  if (id != "merge." + std::to_string(groups_.size()))
    throw std::invalid_argument("group " + id + " out of order");
  ClusterGroup group;
  group.num_images = images;
  group.memory_mib = mib;
  while (*rest >> list) {
    const size_t eq = list.find('=');
    const std::string name = list.substr(0, eq);
    (name == "kernels" ? group.kernels
     : name == "links" ? group.links
                       : group.extra_images) = ReadNumbers(list.substr(eq + 1));
  }
  groups_.push_back(std::move(group));
  memory_mib_[id] = mib;
  return true;
}

std::string TmrMapperStages::GroupRecord(int g) const {
  const ClusterGroup& group = groups_.at(g);
  TmrMapperOptions options = o_;
  options.merge.adjust_join = false;  // the join's, not the group's
  OptionTable table;
  options.AddTo(&table);
  std::string results;
  for (const TmrMapperTask& task : PlannedTasks()) {
    if (std::count(group.kernels.begin(), group.kernels.end(), task.kernel))
      results += ReadFileToString(Model(task) + ".result");
  }
  std::ostringstream record;
  record << GroupContent(group) << "\ntask results " << std::hex
         << std::hash<std::string>()(results) << "\n"
         << table.Values(OptionTable::Rows::kResults);
  return record.str();
}

bool TmrMapperStages::GroupsFitTheTree() const {
  const int num_images = static_cast<int>(tree_.image_ids.size());
  std::vector<int> times_grouped(tree_.kernels.size(), 0);
  auto in_range = [](const std::vector<int>& values, int size) {
    return std::all_of(values.begin(), values.end(),
                       [size](int v) { return v >= 0 && v < size; });
  };
  for (int g = 0; g < static_cast<int>(groups_.size()); ++g) {
    const ClusterGroup& group = groups_[g];
    // Links name later groups, each once.
    int previous = g;
    for (const int h : group.links) {
      if (h <= previous) return false;
      previous = h;
    }
    if (!in_range(group.kernels, static_cast<int>(times_grouped.size())) ||
        !in_range(group.extra_images, num_images) ||
        !in_range(group.links, static_cast<int>(groups_.size())))
      return false;
    if (!group.link_seams.empty() &&
        group.link_seams.size() != group.links.size())
      return false;
    for (const std::vector<int>& seam : group.link_seams)
      if (!in_range(seam, num_images)) return false;
    for (const int k : group.kernels) ++times_grouped[k];
  }
  return groups_.empty()
             ? seam_images_.empty()
             : in_range(seam_images_, num_images) &&
                   std::all_of(times_grouped.begin(), times_grouped.end(),
                               [](int t) { return t == 1; });
}

std::string TmrMapperStages::UnfinishedTaskOfGroup(
    int g, const std::vector<TmrMapperTask>& tasks) const {
  const std::vector<int>& kernels = groups_.at(g).kernels;
  for (const TmrMapperTask& task : tasks) {
    if (!task.finished &&
        std::count(kernels.begin(), kernels.end(), task.kernel))
      return task.id;
  }
  return "";
}

bool TmrMapperStages::GroupMerged(int g) const {
  const std::string text = ReadFileToString(work_.GroupModels(g) + ".result");
  const std::string record = GroupRecord(g);
  int num_models = -1;
  if (text.rfind(record, 0) != 0 ||
      !(std::istringstream(text.substr(record.size())) >> num_models))
    return false;
  for (int m = 0; m < num_models; ++m) {
    if (!fs::is_directory(fs::path(work_.GroupModels(g)) / std::to_string(m)))
      return false;
  }
  return true;
}

bool TmrMapperStages::MergeGroup(int g, int num_threads, const Record& record,
                                 const Progress& progress,
                                 std::string* error) const {
  const std::string name = "group " + std::to_string(g);
  if (GroupMerged(g)) {
    if (progress) progress(name + ": merged by an earlier run");
    return true;
  }
  if (const std::string task = UnfinishedTaskOfGroup(g, Tasks());
      !task.empty()) {
    return Fail("merge." + std::to_string(g) + " waits for task " + task +
                    " of its clusters; run it first (tmr_mapper run_task)",
                error);
  }
  const ClusterGroup& group = groups_.at(g);
  auto group_record = [&](TmrTaskReport row) {
    row.name = name + ": " + row.name;
    record(row);
  };
  const auto start = Clock::now();
  const std::vector<int> images = GroupImages(group);
  const auto cache = LoadTaskDatabaseCache(
      o_.database_path, ImageIdsOf(tree_, images), work_.GroupDatabase(g),
      o_.mapper.min_num_matches, o_.mapper.ignore_watermarks, error);
  if (!cache) return false;
  const int n = static_cast<int>(images.size());
  group_record(
      TmrTaskReport{"load correspondences", n, n, SecondsSince(start), true,
                    std::to_string(group.kernels.size()) + " clusters"});
  std::vector<std::shared_ptr<colmap::Reconstruction>> models =
      MergeClusters(group.kernels, cache, num_threads, group_record, progress);
  for (auto& part : PartModels(&group.kernels)) models.push_back(part);
  std::vector<std::string> names;
  for (const int i : images) names.push_back(tree_.image_names.at(i));
  const SceneAssembler assembler(AssemblyOptions(o_, num_threads), cache,
                                 work_.GroupDatabase(g), names, group_record);
  const auto scenes = assembler.Assemble(models, /*drop_small_models=*/false);
  const fs::path folder(work_.GroupModels(g));
  std::error_code ec;
  fs::remove(work_.GroupModels(g) + ".result", ec);
  fs::remove_all(folder, ec);
  fs::create_directories(folder, ec);
  for (size_t m = 0; m < scenes.size(); ++m) {
    const std::string path = (folder / std::to_string(m)).string();
    if (!WriteModelAtomically(*scenes[m], path))
      return Fail("cannot write model '" + path + "'", error);
  }
  if (!WriteFileAtomically(
          work_.GroupModels(g) + ".result",
          GroupRecord(g) + std::to_string(scenes.size()) + " models\n"))
    return Fail("cannot write in '" + work_.folder().string() + "'", error);
  fs::remove(work_.GroupDatabase(g), ec);
  size_t registered = 0;
  for (const auto& scene : scenes) registered += scene->NumRegImages();
  group_record(TmrTaskReport{"merged", n, static_cast<int>(registered),
                             SecondsSince(start), true,
                             std::to_string(scenes.size()) + " models"});
  return true;
}

}  // namespace tmr
