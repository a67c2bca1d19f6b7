// Copyright (c) 2026, the tmr authors. BSD-3-Clause.
#include "sfm/reconstruction_task.h"

#include <colmap/controllers/incremental_pipeline.h>
#include <colmap/scene/database.h>
#include <colmap/scene/reconstruction_manager.h>

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <unordered_set>

#include "io/model_files.h"
#include "tmr/io/atomic_file.h"

namespace tmr {

bool SaveTaskResult(const ReconstructionTaskResult& result,
                    const std::string& path) {
  std::ostringstream out;
  out << "tmr-task-result 1\n"
      << result.success << " " << result.num_images << " "
      << result.num_registered << " " << result.seconds << " "
      << result.num_registered_in_parts << " " << result.part_models.size()
      << "\n";
  for (const std::string& part : result.part_models) out << part << "\n";
  out << result.message << "\nend\n";
  return WriteFileAtomically(path, out.str());
}

bool LoadTaskResult(const std::string& path, ReconstructionTaskResult* result) {
  std::ifstream in(path);
  std::string header;
  size_t num_parts = 0;
  ReconstructionTaskResult r;
  if (!std::getline(in, header) || header != "tmr-task-result 1") return false;
  if (!(in >> r.success >> r.num_images >> r.num_registered >> r.seconds >>
        r.num_registered_in_parts >> num_parts))
    return false;
  in.ignore(1);
  for (size_t i = 0; i < num_parts; ++i) {
    std::string part;
    if (!std::getline(in, part) || !std::filesystem::is_directory(part))
      return false;
    r.part_models.push_back(part);
  }
  std::string end;
  if (!std::getline(in, r.message) || !std::getline(in, end) || end != "end")
    return false;
  *result = std::move(r);
  return true;
}

std::vector<std::shared_ptr<colmap::Reconstruction>> DisjointModels(
    colmap::ReconstructionManager& manager) {
  std::vector<std::shared_ptr<colmap::Reconstruction>> models;
  for (size_t i = 0; i < manager.Size(); ++i) models.push_back(manager.Get(i));
  std::stable_sort(models.begin(), models.end(),
                   [](const auto& a, const auto& b) {
                     return a->NumRegImages() > b->NumRegImages();
                   });
  std::unordered_set<colmap::image_t> held;
  for (const auto& model : models) {
    const std::vector<colmap::image_t> images = model->RegImageIds();
    for (const colmap::image_t id : images) {
      if (!held.insert(id).second)
        model->DeRegisterFrame(model->Image(id).FrameId());
    }
  }
  return models;
}

namespace {

// Smallest model worth keeping from the rest of a task.
constexpr int kMinPartImages = 3;

// A model with this share of the task's images ends the search for an
// initial pair; the rest of a kernel is mapped on its own (MapRest),
// which costs less than another attempt at the whole kernel.
constexpr double kEnoughShare = 0.5;

bool IsHalo(const std::vector<colmap::image_t>& halo_images,
            colmap::image_t image_id) {
  return std::find(halo_images.begin(), halo_images.end(), image_id) !=
         halo_images.end();
}

bool Registered(const colmap::Reconstruction& model, colmap::image_t image_id) {
  return model.ExistsImage(image_id) && model.Image(image_id).HasPose();
}

// The images of `images` that `model` does not register, halo images aside.
int NumLeftOut(const std::vector<colmap::Image>& images,
               const colmap::Reconstruction& model,
               const std::vector<colmap::image_t>& halo_images) {
  int n = 0;
  for (const colmap::Image& image : images) {
    n += !IsHalo(halo_images, image.ImageId()) &&
         !Registered(model, image.ImageId());
  }
  return n;
}

// The images of the task database (`images`) that `model` does not
// register, except `halo_images`, mapped from scratch: the models of at least
// kMinPartImages images, largest first.
std::vector<std::shared_ptr<colmap::Reconstruction>> MapRest(
    const colmap::IncrementalPipelineOptions& mapper_options,
    const std::string& task_database, const std::vector<colmap::Image>& images,
    const colmap::Reconstruction& model,
    const std::vector<colmap::image_t>& halo_images) {
  auto options =
      std::make_shared<colmap::IncrementalPipelineOptions>(mapper_options);
  options->multiple_models = true;
  options->extract_colors = false;
  options->min_model_size = kMinPartImages;
  options->image_names.clear();
  for (const colmap::Image& image : images) {
    if (!IsHalo(halo_images, image.ImageId()) &&
        !Registered(model, image.ImageId()))
      options->image_names.push_back(image.Name());
  }
  auto manager = std::make_shared<colmap::ReconstructionManager>();
  colmap::IncrementalPipeline controller(
      options, colmap::Database::Open(task_database), manager);
  controller.Run();
  std::vector<std::shared_ptr<colmap::Reconstruction>> parts;
  for (const auto& part : DisjointModels(*manager)) {
    if (static_cast<int>(part->NumRegImages()) >= kMinPartImages)
      parts.push_back(part);
  }
  return parts;
}

// One run of COLMAP's mapper controller on the task database from an
// initial pair (-1: COLMAP's choice), continuing `base_model` if given; the
// largest model, or null.
std::shared_ptr<colmap::Reconstruction> MapFromInitialPair(
    const colmap::IncrementalPipelineOptions& mapper_options,
    const std::string& task_database, const std::string& base_model,
    const std::pair<int, int>& initial_pair) {
  auto options =
      std::make_shared<colmap::IncrementalPipelineOptions>(mapper_options);
  options->multiple_models = false;
  options->extract_colors = false;
  options->image_names.clear();
  options->init_image_id1 = initial_pair.first;
  options->init_image_id2 = initial_pair.second;
  auto manager = std::make_shared<colmap::ReconstructionManager>();
  if (!base_model.empty()) {
    const size_t index = manager->Add();
    manager->Get(index)->ReadBinary(base_model);
  }
  colmap::IncrementalPipeline controller(
      options, colmap::Database::Open(task_database), manager);
  controller.Run();
  std::shared_ptr<colmap::Reconstruction> largest;
  for (size_t i = 0; i < manager->Size(); ++i) {
    if (!largest || manager->Get(i)->NumRegImages() > largest->NumRegImages())
      largest = manager->Get(i);
  }
  return largest;
}

std::string DescribePair(const std::pair<int, int>& pair) {
  return pair.first < 0    ? "automatic initial pair"
         : pair.second < 0 ? "initial image " + std::to_string(pair.first)
                           : "initial pair " + std::to_string(pair.first) +
                                 "+" + std::to_string(pair.second);
}

std::string DescribeConsistency(const MatchConsistency& c) {
  std::ostringstream out;
  out.precision(2);
  out << std::fixed << 100.0 * c.InconsistentShare()
      << "% of verified matches and " << c.num_inconsistent_pairs
      << " pairs inconsistent";
  return out.str();
}

// A kernel model that its own verified matches contradict
// (CheckMatchConsistency) is mapped again: first from the same initial pair
// with the intrinsics held at their priors (where COLMAP's mapper went
// wrong, it had traded focal length against depth from the initial pair on:
// docs/mapper.md, step 3; skipped when the task holds them already), then
// from each other candidate pair. A redo replaces the model when it
// contradicts fewer matches and registers at least 90% as many images; the
// first consistent one ends the search, and so does a redo that gives the
// same model again (as many images, within 2% as many contradicted
// matches): what contradicts it then is the photos' (forward motion, lens
// distortion), not the initial pair's. Appends what happened to `how`.
void RedoIfInconsistent(
    const colmap::IncrementalPipelineOptions& mapper_options,
    const std::string& task_database,
    const std::vector<std::pair<int, int>>& candidate_pairs,
    const std::pair<int, int>& initial_pair,
    const MatchConsistencyOptions& check,
    std::shared_ptr<colmap::Reconstruction>* model, std::string* how) {
  const auto consistency = [&](const colmap::Reconstruction& m) {
    // The task's own database (COLMAP writes to what it opens).
    return CheckMatchConsistency(m, *colmap::Database::Open(task_database),
                                 check);
  };
  MatchConsistency best = consistency(**model);
  if (best.IsConsistent(check)) return;
  *how += "; " + DescribeConsistency(best);
  colmap::IncrementalPipelineOptions held = mapper_options;
  held.ba_refine_focal_length = false;
  held.ba_refine_principal_point = false;
  held.ba_refine_extra_params = false;
  const bool holds_intrinsics = !mapper_options.ba_refine_focal_length &&
                                !mapper_options.ba_refine_principal_point &&
                                !mapper_options.ba_refine_extra_params;
  std::vector<
      std::pair<const colmap::IncrementalPipelineOptions*, std::pair<int, int>>>
      redos;
  if (!holds_intrinsics) redos.push_back({&held, initial_pair});
  for (const auto& pair : candidate_pairs)
    if (pair != initial_pair) redos.push_back({&mapper_options, pair});
  for (const auto& [options, pair] : redos) {
    *how += "; redo from " + DescribePair(pair) +
            (options == &held ? " with intrinsics held: " : ": ");
    const auto redo = MapFromInitialPair(*options, task_database, "", pair);
    if (!redo || redo->NumRegImages() < 2) {
      *how += "failed";
      continue;
    }
    const MatchConsistency c = consistency(*redo);
    const bool same_model =
        redo->NumRegImages() == (*model)->NumRegImages() &&
        std::abs(c.num_inconsistent - best.num_inconsistent) * 50 <=
            best.num_inconsistent;
    const bool better =
        c.InconsistentShare() < best.InconsistentShare() &&
        10 * redo->NumRegImages() >= 9 * (*model)->NumRegImages();
    *how += std::to_string(redo->NumRegImages()) + " images, " +
            DescribeConsistency(c) + (better ? ", taken" : ", not taken");
    if (same_model && !better) {
      *how += "; the same model again: kept";
      return;
    }
    if (!better) continue;
    *model = redo;
    best = c;
    if (best.IsConsistent(check)) return;
  }
}

}  // namespace

ReconstructionTaskResult RunReconstructionTask(
    const colmap::IncrementalPipelineOptions& mapper_options,
    const std::string& task_database, const std::string& base_model,
    const std::vector<std::pair<int, int>>& initial_pairs,
    const MatchConsistencyOptions* kernel_check,
    const std::string& output_model,
    const std::vector<colmap::image_t>& halo_images) {
  const auto start = std::chrono::steady_clock::now();
  ReconstructionTaskResult result;
  const std::vector<colmap::Image> images =
      colmap::Database::Open(task_database)->ReadAllImages();
  result.num_images = static_cast<int>(images.size());
  // With a base model only one attempt makes sense; without, each initial
  // pair in turn and then COLMAP's own choice.
  std::vector<std::pair<int, int>> attempts;
  if (base_model.empty()) {
    attempts.assign(
        initial_pairs.begin(),
        initial_pairs.begin() + std::min<size_t>(initial_pairs.size(), 2));
  }
  attempts.emplace_back(-1, -1);
  // Keep the best model over the attempts; stop at one that registers
  // half of the task's images.
  std::shared_ptr<colmap::Reconstruction> best;
  std::pair<int, int> best_pair(-1, -1);
  for (const auto& pair : attempts) {
    const auto model =
        MapFromInitialPair(mapper_options, task_database, base_model, pair);
    if (model && (!best || model->NumRegImages() > best->NumRegImages())) {
      best = model;
      best_pair = pair;
    }
    if (best && best->NumRegImages() >= kEnoughShare * result.num_images) break;
  }
  std::string how = DescribePair(best_pair);
  if (best && best->NumRegImages() >= 2 && base_model.empty() && kernel_check)
    RedoIfInconsistent(mapper_options, task_database, attempts, best_pair,
                       *kernel_check, &best, &how);
  std::vector<std::shared_ptr<colmap::Reconstruction>> parts;
  if (best && best->NumRegImages() >= 2 &&
      NumLeftOut(images, *best, halo_images) >= kMinPartImages) {
    parts = MapRest(mapper_options, task_database, images, *best, halo_images);
  }
  // A kernel's model is its largest. COLMAP keeps the first model of a run
  // whatever its size, so a seeded model can stall at a few images where
  // the rest then gives one of most of the kernel (docs/mapper.md, step 3).
  if (best && base_model.empty() && !parts.empty() &&
      parts.front()->NumRegImages() > best->NumRegImages()) {
    how += "; stalled at " + std::to_string(best->NumRegImages()) +
           " images, the largest model of the rest taken instead";
    std::swap(best, parts.front());
    if (static_cast<int>(parts.front()->NumRegImages()) < kMinPartImages)
      parts.erase(parts.begin());
    std::stable_sort(parts.begin(), parts.end(),
                     [](const auto& a, const auto& b) {
                       return a->NumRegImages() > b->NumRegImages();
                     });
  }
  if (best && best->NumRegImages() >= 2) {
    result.num_registered = static_cast<int>(best->NumRegImages());
    result.success = WriteModelAtomically(*best, output_model);
    result.message = result.success ? how : "cannot write " + output_model;
  }
  if (result.success) {
    for (const auto& part : parts) {
      const std::string path = output_model + "_part" +
                               std::to_string(result.part_models.size() + 1);
      if (!WriteModelAtomically(*part, path)) continue;
      result.part_models.push_back(path);
      result.num_registered_in_parts += static_cast<int>(part->NumRegImages());
    }
  }
  if (!result.success && result.message.empty())
    result.message = "no initial pair worked";
  result.seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start)
          .count();
  return result;
}

}  // namespace tmr
