// Copyright (c) 2026, the tmr authors. BSD-3-Clause.
// How the scene assembly sees two models: the verified pairs between them
// (ranking merge candidates, weak links) and the two alignment rules tried
// in turn (shared tracks, then images registered on the scene's points).
#include <algorithm>
#include <unordered_map>

#include "merge/registration_alignment.h"
#include "merge/scene_assembly.h"

namespace tmr {

std::vector<SceneAssembler::ModelLink> SceneAssembler::Links(
    const colmap::Reconstruction& model,
    const std::vector<const colmap::Reconstruction*>& scenes) const {
  std::unordered_map<colmap::image_t, int> owner;
  for (int i = 0; i < static_cast<int>(scenes.size()); ++i) {
    for (const colmap::image_t id : scenes[i]->RegImageIds()) owner[id] = i;
  }
  std::vector<ModelLink> links(scenes.size());
  for (const colmap::image_t id : model.RegImageIds()) {
    const auto partners = image_links_.find(id);
    if (partners == image_links_.end()) continue;
    for (const auto& [other, num_correspondences] : partners->second) {
      const auto it = owner.find(other);
      if (it == owner.end()) continue;
      ++links[it->second].num_pairs;
      links[it->second].num_correspondences += num_correspondences;
    }
  }
  return links;
}

std::vector<int> SceneAssembler::LinkedScenes(
    const colmap::Reconstruction& model, const Scenes& scenes) const {
  std::vector<const colmap::Reconstruction*> models;
  for (const AssemblyScene& scene : scenes) models.push_back(scene.model.get());
  const std::vector<ModelLink> links = Links(model, models);
  std::vector<int> order;
  for (int i = 0; i < static_cast<int>(scenes.size()); ++i)
    if (links[i].num_pairs > 0) order.push_back(i);
  // A stable sort keeps the larger scene first on a tie.
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) {
    return links[a].num_correspondences > links[b].num_correspondences;
  });
  return order;
}

ModelAlignment SceneAssembler::Align(const colmap::Reconstruction& scene,
                                     const colmap::Reconstruction& model,
                                     bool images_first) const {
  const colmap::CorrespondenceGraph& graph = *cache_->CorrespondenceGraph();
  RegistrationAlignmentOptions registration;
  registration.max_images = o_.register_images;
  registration.min_num_inliers = o_.mapper.mapper.abs_pose_min_num_inliers;
  registration.seed = o_.seed;
  if (images_first && o_.register_images > 0) {
    const ModelAlignment by_images =
        AlignModelsByRegisteredImages(scene, model, graph, registration);
    if (by_images.success) return by_images;
  }
  ModelAlignmentOptions tracks;
  tracks.min_shared_tracks = o_.min_shared_tracks;
  tracks.seed = registration.seed;
  const ModelAlignment by_tracks =
      AlignModelsBySharedTracks(scene, model, graph, tracks);
  if (by_tracks.success || o_.register_images == 0) return by_tracks;
  ModelAlignment by_images =
      AlignModelsByRegisteredImages(scene, model, graph, registration);
  if (!by_images.success) {
    by_images.reason = by_tracks.reason + "; " + by_images.reason;
  }
  // The weak-link report gives the shared tracks of the track rule.
  by_images.num_shared_tracks = by_tracks.num_shared_tracks;
  by_images.num_inliers = by_tracks.num_inliers;
  return by_images;
}

std::vector<TmrWeakLink> SceneAssembler::WeakLinks(
    const std::vector<std::shared_ptr<colmap::Reconstruction>>& scenes) const {
  std::vector<const colmap::Reconstruction*> models;
  for (const auto& scene : scenes) models.push_back(scene.get());
  std::vector<TmrWeakLink> weak_links;
  for (int j = 1; j < static_cast<int>(scenes.size()); ++j) {
    const std::vector<ModelLink> links = Links(*scenes[j], models);
    for (int i = 0; i < j; ++i) {
      if (links[i].num_pairs == 0) continue;
      const ModelAlignment a = Align(*scenes[i], *scenes[j]);
      weak_links.push_back({i, j, links[i].num_pairs,
                            links[i].num_correspondences, a.num_shared_tracks,
                            a.num_registered_images, a.num_supporting_images,
                            a.success
                                ? "they align now (after the last refinement)"
                                : a.reason});
    }
  }
  std::sort(weak_links.begin(), weak_links.end(),
            [](const TmrWeakLink& a, const TmrWeakLink& b) {
              return std::make_pair(a.model1, a.model2) <
                     std::make_pair(b.model1, b.model2);
            });
  return weak_links;
}

}  // namespace tmr
