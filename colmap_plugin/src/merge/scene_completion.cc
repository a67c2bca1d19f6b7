// Copyright (c) 2026, the tmr authors. BSD-3-Clause.
// The completion passes of SceneAssembler: registering, into the scenes,
// the images no scene holds (CompleteScenes), and mapping from scratch what
// is left after that (ReconstructLeftovers).
#include <colmap/scene/database.h>
#include <colmap/scene/reconstruction_manager.h>
#include <colmap/sfm/incremental_mapper.h>

#include <algorithm>
#include <chrono>
#include <limits>
#include <optional>
#include <unordered_map>
#include <unordered_set>

#include "merge/scene_assembly.h"
#include "sfm/reconstruction_task.h"
#include "tmr/util/process.h"

namespace tmr {
namespace {

using Clock = std::chrono::steady_clock;

// Names of the images that the first `count` models register (all: every
// model).
std::unordered_set<std::string> HeldImageNames(
    const std::vector<AssemblyScene>& scenes,
    size_t count = std::numeric_limits<size_t>::max()) {
  std::unordered_set<std::string> held;
  for (size_t i = 0; i < std::min(count, scenes.size()); ++i) {
    const colmap::Reconstruction& model = *scenes[i].model;
    for (const colmap::image_t id : model.RegImageIds())
      held.insert(model.Image(id).Name());
  }
  return held;
}

// The images outside `before` with at least `min_matched` keypoints
// matched to keypoints of images in `before`. Only they can see that many
// points of the scene before completion (RemoveUnanchoredImages); any other
// image completion registers is placed on points that images registered
// after it triangulated, and is taken out again.
std::unordered_set<colmap::image_t> ImagesMatchedToScene(
    const colmap::DatabaseCache& cache,
    const std::unordered_map<colmap::image_t,
                             std::vector<std::pair<colmap::image_t, int>>>&
        image_links,
    const std::unordered_set<colmap::image_t>& before, int min_matched) {
  const colmap::CorrespondenceGraph& graph = *cache.CorrespondenceGraph();
  std::unordered_set<colmap::image_t> matched;
  for (const auto& [id, links] : image_links) {
    if (before.count(id)) continue;
    int upper_bound = 0;
    for (const auto& [other, num_correspondences] : links)
      if (before.count(other)) upper_bound += num_correspondences;
    if (upper_bound < min_matched) continue;
    int keypoints = 0;
    const colmap::point2D_t num_points2D = cache.Image(id).NumPoints2D();
    for (colmap::point2D_t idx = 0;
         idx < num_points2D && keypoints < min_matched; ++idx) {
      const auto range = graph.FindCorrespondences(id, idx);
      for (const auto* corr = range.beg; corr < range.end; ++corr) {
        if (before.count(corr->image_id)) {
          ++keypoints;
          break;
        }
      }
    }
    if (keypoints >= min_matched) matched.insert(id);
  }
  return matched;
}

}  // namespace

int RemoveUnanchoredImages(const std::unordered_set<colmap::image_t>& before,
                           int min_anchored, colmap::Reconstruction* scene) {
  std::vector<colmap::image_t> unanchored;
  for (const colmap::image_t id : scene->RegImageIds()) {
    if (before.count(id)) continue;
    int anchored = 0;
    for (const colmap::Point2D& point : scene->Image(id).Points2D()) {
      if (!point.HasPoint3D()) continue;
      for (const auto& element :
           scene->Point3D(point.point3D_id).track.Elements()) {
        if (before.count(element.image_id)) {
          ++anchored;
          break;
        }
      }
    }
    if (anchored < min_anchored) unanchored.push_back(id);
  }
  for (const colmap::image_t id : unanchored)
    scene->DeRegisterFrame(scene->Image(id).FrameId());
  return static_cast<int>(unanchored.size());
}

// Registers into each scene model, largest first, the images that no model
// holds yet (kernel images the kernel task could not register, leaves of
// failed leaf tasks, unclustered images) and those of smaller models that
// no merge joined to it, as COLMAP's mapper continues a model: next image
// by visible points, registration (on the scene's points, else
// structure-less), triangulation, local refinement. It
// works on the loaded correspondences; the one global adjustment follows
// in RefineMergedScenes. An image a smaller model gave up leaves that
// model.
void SceneAssembler::CompleteScenes(Scenes* scenes,
                                    bool keep_unless_grown) const {
  SortBySize(scenes);
  const colmap::IncrementalPipelineOptions& colmap_options = o_.mapper;
  const colmap::IncrementalMapper::Options options = colmap_options.Mapper();
  const auto triangulation = colmap_options.Triangulation();
  const auto local_ba = colmap_options.LocalBundleAdjustment();
  std::vector<bool> structure_less_flags = {false};
  if (colmap_options.structure_less_registration_only)
    structure_less_flags = {true};
  else if (colmap_options.structure_less_registration_fallback)
    structure_less_flags = {false, true};
  for (int i = 0; i < static_cast<int>(scenes->size()); ++i) {
    const auto start = Clock::now();
    AssemblyScene& assembly_scene = (*scenes)[i];
    const std::shared_ptr<colmap::Reconstruction>& scene = assembly_scene.model;
    const int before = static_cast<int>(scene->NumRegImages());
    if (before < 2) continue;
    const std::vector<colmap::image_t>& held = scene->RegImageIds();
    const std::unordered_set<colmap::image_t> before_ids(held.begin(),
                                                         held.end());
    const std::optional<colmap::Reconstruction> kept =
        keep_unless_grown ? std::make_optional(*scene) : std::nullopt;
    // Larger scenes keep their images; smaller models offer theirs.
    std::unordered_set<colmap::image_t> held_elsewhere;
    for (const std::string& name : HeldImageNames(*scenes, i)) {
      if (const colmap::Image* image = cache_->FindImageWithName(name))
        held_elsewhere.insert(image->ImageId());
    }
    const std::unordered_set<colmap::image_t> reachable = ImagesMatchedToScene(
        *cache_, image_links_, before_ids, options.abs_pose_min_num_inliers);
    colmap::IncrementalMapper mapper(cache_);
    mapper.BeginReconstruction(scene);
    // COLMAP caps the attempts per image (Mapper.max_reg_trials), so the
    // loop ends when no candidate is left. As in COLMAP's mapper, an image
    // is registered on the scene's points first and, where none can be,
    // on its matches to registered images (structure-less registration).
    bool registered = true;
    while (registered) {
      registered = false;
      for (const bool structure_less : structure_less_flags) {
        for (const colmap::image_t id :
             mapper.FindNextImages(options, structure_less)) {
          if (held_elsewhere.count(id) || !reachable.count(id) ||
              !(structure_less
                    ? mapper.RegisterNextStructureLessImage(options, id)
                    : mapper.RegisterNextImage(options, id)))
            continue;
          mapper.TriangulateImage(triangulation, id);
          mapper.IterativeLocalRefinement(
              colmap_options.ba_local_max_refinements,
              colmap_options.ba_local_max_refinement_change, options, local_ba,
              triangulation, id);
          registered = true;
          break;
        }
        if (registered) break;
      }
    }
    mapper.EndReconstruction(/*discard=*/false);
    const int removed = RemoveUnanchoredImages(
        before_ids, options.abs_pose_min_num_inliers, scene.get());
    const int added = static_cast<int>(scene->NumRegImages()) - before;
    if (kept && added == 0) *scene = *kept;
    int taken = 0;
    for (int j = i + 1; j < static_cast<int>(scenes->size()); ++j) {
      colmap::Reconstruction& smaller = *(*scenes)[j].model;
      for (const colmap::image_t id :
           std::vector<colmap::image_t>(smaller.RegImageIds())) {
        if (!before_ids.count(id) && scene->ExistsImage(id) &&
            scene->Image(id).HasPose()) {
          smaller.DeRegisterFrame(smaller.Image(id).FrameId());
          ++taken;
        }
      }
    }
    if (added > 0) assembly_scene.unrefined = true;
    record_({"complete model " + std::to_string(i), before,
             static_cast<int>(scene->NumRegImages()), SecondsSince(start), true,
             std::to_string(added) + " images added" +
                 (taken > 0 ? " (" + std::to_string(taken) +
                                  " of them from smaller models)"
                            : "") +
                 (removed > 0
                      ? "; " + std::to_string(removed) +
                            " taken out again (fewer than " +
                            std::to_string(options.abs_pose_min_num_inliers) +
                            " points of the scene before)"
                      : "")});
  }
  // Models that gave up all but one image are gone.
  scenes->erase(std::remove_if(scenes->begin(), scenes->end(),
                               [](const AssemblyScene& scene) {
                                 return scene.model->NumRegImages() < 2;
                               }),
                scenes->end());
  SortBySize(scenes);
}

// Images that no model holds yet get COLMAP's mapper from scratch, as
// `colmap mapper` would on them alone (several models if need be): parts
// of the scene that no kernel reached, or kernels COLMAP could only partly
// reconstruct. Returns whether it added a model.
bool SceneAssembler::ReconstructLeftovers(Scenes* scenes) const {
  const auto start = Clock::now();
  const auto held = HeldImageNames(*scenes);
  auto options = std::make_shared<colmap::IncrementalPipelineOptions>(
      o_.mapper);
  options->extract_colors = false;
  for (const std::string& name : image_names_) {
    if (!held.count(name)) options->image_names.push_back(name);
  }
  const int leftovers = static_cast<int>(options->image_names.size());
  if (leftovers < 2) return false;
  auto manager = std::make_shared<colmap::ReconstructionManager>();
  colmap::IncrementalPipeline controller(
      options, colmap::Database::Open(merge_database_), manager);
  controller.Run();
  int registered = 0, added = 0;
  for (const auto& model : DisjointModels(*manager)) {
    if (model->NumRegImages() < 2) continue;
    registered += static_cast<int>(model->NumRegImages());
    scenes->push_back({model, false, model->NumRegImages(), {}});
    ++added;
  }
  record_({"images left over", leftovers, registered, SecondsSince(start), true,
           std::to_string(added) + " new models"});
  SortBySize(scenes);
  return added > 0;
}

}  // namespace tmr
