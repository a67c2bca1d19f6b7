// Copyright (c) 2026, the tmr authors. BSD-3-Clause.
// The scene assembly's first pass: every pair of linked
// models aligned at once, in parallel, then one similarity averaging over
// the graph of models, and each connected part appended into its largest
// model without adjustment between.
#include <colmap/util/threading.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <future>
#include <map>
#include <numeric>
#include <unordered_map>
#include <unordered_set>

#include "merge/scene_assembly.h"
#include "merge/similarity_averaging.h"
#include "sfm/model_edits.h"
#include "tmr/util/futures.h"
#include "tmr/util/process.h"

namespace tmr {
namespace {

using Clock = std::chrono::steady_clock;

// Most points a link carries (evenly spread over its seam).
constexpr size_t kMaxSeamPoints = 2000;

// The points of `model` that `seam_images` observe, in the model's frame,
// and their median viewing distance: where a link to another model is
// measured.
void AddSeamPoints(const colmap::Reconstruction& model,
                   const std::vector<colmap::image_t>& seam_images,
                   SimilarityLink* link) {
  std::unordered_set<colmap::point3D_t> seen;
  std::vector<double> distances;
  for (const colmap::image_t id : seam_images) {
    const colmap::Image& image = model.Image(id);
    const Eigen::Vector3d center = image.ProjectionCenter();
    for (const colmap::Point2D& p : image.Points2D()) {
      if (!p.HasPoint3D() || !seen.insert(p.point3D_id).second) continue;
      const Eigen::Vector3d& xyz = model.Point3D(p.point3D_id).xyz;
      link->points2.push_back(xyz);
      distances.push_back((xyz - center).norm());
    }
  }
  if (link->points2.size() > kMaxSeamPoints) {
    const size_t step = link->points2.size() / kMaxSeamPoints + 1;
    std::vector<Eigen::Vector3d> kept;
    for (size_t i = 0; i < link->points2.size(); i += step)
      kept.push_back(link->points2[i]);
    link->points2 = std::move(kept);
  }
  if (distances.empty()) return;
  auto middle = distances.begin() + distances.size() / 2;
  std::nth_element(distances.begin(), middle, distances.end());
  link->scale2 = std::max(*middle, 1e-9);
}

// Two models that verified pairs link, or that share images (model1 <
// model2): their verified image pairs and matches, and model2's images on
// the seam.
struct ModelPair {
  int num_pairs = 0;
  int num_correspondences = 0;
  std::vector<colmap::image_t> seam_images;
};

std::map<std::pair<int, int>, ModelPair> LinkedPairs(
    const std::vector<const colmap::Reconstruction*>& models,
    const std::unordered_map<colmap::image_t,
                             std::vector<std::pair<colmap::image_t, int>>>&
        image_links) {
  // The models that register each image: one, or several for a halo image.
  std::unordered_map<colmap::image_t, std::vector<int>> owners;
  for (int m = 0; m < static_cast<int>(models.size()); ++m)
    for (const colmap::image_t id : models[m]->RegImageIds())
      owners[id].push_back(m);
  std::map<std::pair<int, int>, ModelPair> pairs;
  for (int b = 0; b < static_cast<int>(models.size()); ++b) {
    for (const colmap::image_t id : models[b]->RegImageIds()) {
      std::unordered_set<int> linked;
      for (const int a : owners.at(id)) {
        if (a < b && linked.insert(a).second)
          pairs[{a, b}].seam_images.push_back(id);
      }
      const auto partners = image_links.find(id);
      if (partners == image_links.end()) continue;
      for (const auto& [other, num_correspondences] : partners->second) {
        const auto it = owners.find(other);
        if (it == owners.end()) continue;
        for (const int a : it->second) {
          if (a >= b) continue;
          ModelPair& pair = pairs[{a, b}];
          ++pair.num_pairs;
          pair.num_correspondences += num_correspondences;
          if (linked.insert(a).second) pair.seam_images.push_back(id);
        }
      }
    }
  }
  return pairs;
}

// Keeps one copy of each image that the first n scenes share (halos), then
// appends each of those scenes that is not its part's root (placed.part)
// into the root, moved by its placement. Returns the number of parts, and
// in *num_copies the copies taken out.
int AppendIntoParts(const SimilarityAveraging& placed, int n,
                    std::vector<AssemblyScene>* scenes, int* num_copies) {
  std::vector<colmap::Reconstruction*> editable;
  for (int m = 0; m < n; ++m) editable.push_back((*scenes)[m].model.get());
  *num_copies = KeepOneCopyOfEachImage(editable);
  int num_parts = 0;
  for (int m = 0; m < n; ++m) {
    const int root = placed.part[m];
    if (root == m) {
      ++num_parts;
      continue;
    }
    AppendReconstruction(*(*scenes)[m].model, placed.part_from_model[m],
                         (*scenes)[root].model.get());
    (*scenes)[root].unrefined = true;
    (*scenes)[m].model.reset();  // freed here unless the caller holds it
  }
  return num_parts;
}

}  // namespace

PlacedModels PlaceModelPairs(int num_models,
                             const std::vector<ModelPairAlignment>& pairs) {
  std::vector<SimilarityLink> links;
  PlacedModels placed;
  for (size_t p = 0; p < pairs.size(); ++p) {
    if (!pairs[p].link) continue;
    links.push_back(*pairs[p].link);
    placed.link_pair.push_back(p);
  }
  placed.averaging =
      AverageSimilarities(num_models, links, SimilarityAveragingOptions());
  return placed;
}

std::vector<TmrTaskReport> AlignmentRows(
    const std::vector<size_t>& model_sizes,
    const std::vector<ModelPairAlignment>& pairs, const PlacedModels& models,
    size_t num_scenes, int num_copies, double seconds) {
  const SimilarityAveraging& placed = models.averaging;
  const std::vector<size_t>& link_pair = models.link_pair;
  const int num_held = static_cast<int>(
      std::count(placed.accepted.begin(), placed.accepted.end(), true));
  const int num_images = static_cast<int>(
      std::accumulate(model_sizes.begin(), model_sizes.end(), size_t{0}));
  std::vector<TmrTaskReport> rows = {
      {"align " + std::to_string(pairs.size()) + " linked pairs of " +
           std::to_string(model_sizes.size()) + " models at once",
       num_images, num_images, seconds, true,
       std::to_string(link_pair.size()) + " pairs aligned, " +
           std::to_string(num_held) + " held by the similarity averaging; " +
           "scenes: " + std::to_string(num_scenes) +
           (num_copies > 0 ? "; " + std::to_string(num_copies) +
                                 " second copies of images taken out"
                           : "")}};
  for (const ModelPairAlignment& pair : pairs) {
    const int a = static_cast<int>(model_sizes.at(pair.model1));
    const int b = static_cast<int>(model_sizes.at(pair.model2));
    const ModelAlignment& alignment = pair.alignment;
    rows.push_back(
        {"link of models of " + std::to_string(b) + " and " +
             std::to_string(a) + " images",
         b, 0, 0.0, false,
         (alignment.success ? DescribeFit(alignment) : alignment.reason) +
             " (aligned in " +
             std::to_string(std::lround(pair.seconds * 1000)) + " ms)"});
    rows.back().link = {pair.model1, pair.model2, a, b};
  }
  for (size_t l = 0; l < link_pair.size(); ++l) {
    TmrTaskReport& row = rows[1 + link_pair[l]];
    row.success = placed.accepted[l];
    row.num_registered = row.success ? row.num_images : 0;
    row.message =
        row.message + (row.success ? "; " : "; refused: ") + placed.reason[l];
  }
  return rows;
}

std::vector<ModelPairAlignment> SceneAssembler::AlignModelPairs(
    const std::vector<const colmap::Reconstruction*>& models, bool images_first,
    const std::function<bool(int, int)>& wanted) const {
  std::map<std::pair<int, int>, ModelPair> linked =
      LinkedPairs(models, image_links_);
  std::vector<ModelPairAlignment> pairs;
  std::vector<const ModelPair*> seams;
  for (const auto& [key, pair] : linked) {
    if (wanted && !wanted(key.first, key.second)) continue;
    ModelPairAlignment aligned;
    aligned.model1 = key.first;
    aligned.model2 = key.second;
    aligned.num_pairs = pair.num_pairs;
    aligned.num_correspondences = pair.num_correspondences;
    pairs.push_back(std::move(aligned));
    seams.push_back(&pair);
  }
  // Every pair aligned at once (the alignments only read the models).
  colmap::ThreadPool pool(std::max(1, o_.num_threads));
  std::vector<std::shared_future<void>> done;
  for (size_t p = 0; p < pairs.size(); ++p) {
    done.push_back(pool.AddTask([&, p] {
      const auto start = Clock::now();
      ModelPairAlignment& pair = pairs[p];
      pair.alignment =
          Align(*models[pair.model1], *models[pair.model2], images_first);
      if (pair.alignment.success) {
        SimilarityLink link;
        link.model1 = pair.model1;
        link.model2 = pair.model2;
        link.model1_from_model2 = pair.alignment.target_from_source;
        link.weight = pair.num_correspondences;
        AddSeamPoints(*models[pair.model2], seams[p]->seam_images, &link);
        if (!link.points2.empty()) pair.link = std::move(link);
      }
      pair.seconds = SecondsSince(start);
    }));
  }
  WaitForAll(done);
  return pairs;
}

void SceneAssembler::AlignAllScenes(Scenes* scenes) const {
  SortBySize(scenes);
  const auto start = Clock::now();
  // Models too small to move as one block stay out (as in MergeScenes),
  // left to CompleteScenes.
  const size_t min_size = o_.complete_models ? MinModelSize() : 0;
  std::vector<const colmap::Reconstruction*> models;
  std::vector<size_t> sizes;
  for (const AssemblyScene& scene : *scenes) {
    if (scene.model->NumRegImages() < min_size) break;
    models.push_back(scene.model.get());
    sizes.push_back(scene.model->NumRegImages());
  }
  const int n = static_cast<int>(models.size());
  if (n < 2) return;
  const std::vector<ModelPairAlignment> pairs =
      AlignModelPairs(models, /*images_first=*/false);
  const PlacedModels placed_models = PlaceModelPairs(n, pairs);
  const SimilarityAveraging& placed = placed_models.averaging;
  // Images that several models register (halos) keep one copy, then each
  // part is appended into its first (largest) model, in one frame.
  int num_copies = 0;
  const int num_parts = AppendIntoParts(placed, n, scenes, &num_copies);
  for (const TmrTaskReport& row :
       AlignmentRows(sizes, pairs, placed_models, num_parts, num_copies,
                     SecondsSince(start)))
    record_(row);
  Scenes kept;
  for (int m = 0; m < static_cast<int>(scenes->size()); ++m) {
    if (m < n && placed.part[m] != m) continue;  // appended above
    AssemblyScene& scene = (*scenes)[m];
    // A merged scene is adjusted once on its longest tracks, then fully in
    // RefineMergedScenes: its full adjustment alone, from the averaged
    // placement, left scattered photos off (docs/mapper.md, step 4).
    if (scene.unrefined) Refine(&scene, /*while_merging=*/true);
    kept.push_back(std::move(scene));
  }
  *scenes = std::move(kept);
  SortBySize(scenes);
}

}  // namespace tmr
