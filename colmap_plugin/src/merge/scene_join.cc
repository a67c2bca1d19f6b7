// Copyright (c) 2026, the tmr authors. BSD-3-Clause.
// The join of a merge stage by parts (docs/distributed.md) from the
// alignments of its linked models: one similarity averaging, one copy of
// each image, a scene per connected part, described piece by piece so that
// the scenes can be written from the whole models one at a time.
#include <algorithm>
#include <chrono>
#include <map>
#include <unordered_map>

#include "merge/scene_assembly.h"
#include "sfm/model_edits.h"
#include "tmr/util/process.h"

namespace tmr {
namespace {

// Why the strongest link between two scenes of a join did not join them.
std::string KeptApart(const ModelPairAlignment& pair, size_t p,
                      const PlacedModels& placed) {
  if (!pair.alignment.success) return pair.alignment.reason;
  if (!pair.link) return "their alignment has no points on the seam";
  const auto link =
      std::find(placed.link_pair.begin(), placed.link_pair.end(), p);
  return "the similarity averaging refused their link: " +
         placed.averaging.reason.at(link - placed.link_pair.begin());
}

}  // namespace

std::vector<JoinedScene> SceneAssembler::PlaceJoin(
    const std::vector<JoinModel>& models, std::vector<ModelPairAlignment> pairs,
    std::vector<TmrWeakLink>* weak_links) const {
  const auto start = std::chrono::steady_clock::now();
  const int n = static_cast<int>(models.size());
  std::sort(pairs.begin(), pairs.end(),
            [](const ModelPairAlignment& a, const ModelPairAlignment& b) {
              return std::make_pair(a.model1, a.model2) <
                     std::make_pair(b.model1, b.model2);
            });
  const PlacedModels placed_models = PlaceModelPairs(n, pairs);
  const SimilarityAveraging& placed = placed_models.averaging;
  std::vector<size_t> sizes;
  for (const JoinModel& model : models) sizes.push_back(model.num_images);
  std::vector<std::unordered_map<colmap::image_t, size_t>> seam_points;
  for (const JoinModel& model : models)
    seam_points.push_back(model.seam_image_points);
  const std::vector<std::vector<colmap::image_t>> dropped =
      DroppedImageCopies(seam_points);
  // Each connected part a scene of its models in order, in its first
  // (largest) model's frame.
  std::vector<JoinedScene> scenes;
  std::vector<int> scene_of_model(n, -1);
  int num_copies = 0;
  for (int m = 0; m < n; ++m) {
    const int root = placed.part.at(m);
    if (root == m) {
      scene_of_model[m] = static_cast<int>(scenes.size());
      scenes.emplace_back();
    } else {
      scene_of_model[m] = scene_of_model.at(root);
    }
    JoinedScene& scene = scenes[scene_of_model[m]];
    scene.pieces.push_back(
        {m, root == m ? colmap::Sim3d() : placed.part_from_model[m],
         dropped[m]});
    scene.num_images += models[m].num_images - dropped[m].size();
    num_copies += static_cast<int>(dropped[m].size());
  }
  if (n >= 2) {  // as AlignAllScenes, nothing to align below two
    for (const TmrTaskReport& row :
         AlignmentRows(sizes, pairs, placed_models, scenes.size(), num_copies,
                       SecondsSince(start)))
      record_(row);
  }

  // Largest first; with several, those below MinModelSize go.
  std::vector<int> order(scenes.size());
  for (size_t s = 0; s < order.size(); ++s) order[s] = static_cast<int>(s);
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) {
    return scenes[a].num_images > scenes[b].num_images;
  });
  int num_dropped = 0, dropped_images = 0;
  while (order.size() > 1 && scenes[order.back()].num_images < MinModelSize()) {
    ++num_dropped;
    dropped_images += static_cast<int>(scenes[order.back()].num_images);
    order.pop_back();
  }
  RecordDroppedModels(num_dropped, dropped_images);
  std::vector<int> output_of_scene(scenes.size(), -1);
  std::vector<JoinedScene> kept;
  for (const int s : order) {
    output_of_scene[s] = static_cast<int>(kept.size());
    kept.push_back(std::move(scenes[s]));
  }

  // Scenes that verified pairs link: the strongest link between them, and
  // why it did not join them.
  std::map<std::pair<int, int>, TmrWeakLink> apart;
  std::map<std::pair<int, int>, int> strongest;
  for (size_t p = 0; p < pairs.size(); ++p) {
    const ModelPairAlignment& pair = pairs[p];
    int a = output_of_scene[scene_of_model[pair.model1]];
    int b = output_of_scene[scene_of_model[pair.model2]];
    if (a < 0 || b < 0 || a == b || pair.num_pairs == 0) continue;
    if (a > b) std::swap(a, b);
    TmrWeakLink& link = apart[{a, b}];
    link.model1 = a;
    link.model2 = b;
    link.num_pairs += pair.num_pairs;
    link.num_correspondences += pair.num_correspondences;
    int& most = strongest[{a, b}];
    if (pair.num_correspondences <= most) continue;
    most = pair.num_correspondences;
    link.num_shared_tracks = pair.alignment.num_shared_tracks;
    link.num_registered_images = pair.alignment.num_registered_images;
    link.num_supporting_images = pair.alignment.num_supporting_images;
    link.reason = KeptApart(pair, p, placed_models);
  }
  weak_links->clear();
  for (auto& [key, link] : apart) weak_links->push_back(std::move(link));
  return kept;
}

}  // namespace tmr
