// Copyright (c) 2026, the tmr authors. BSD-3-Clause.
#include <colmap/scene/reconstruction.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <random>
#include <unordered_set>
#include <vector>

#include "controllers/tmr_mapper_stages.h"
#include "io/model_files.h"
#include "sfm/model_edits.h"
#include "sfm/reconstruction_task.h"
#include "tmr/colmap/synthetic_task_results.h"

namespace tmr {
namespace {

constexpr double kPi = 3.14159265358979323846;

// A generator for one (task, item) pair, whatever the order of the calls:
// the kernel images of a leaf model take their kernel model's noise.
std::mt19937_64 Generator(uint64_t seed, int kernel, int leaf, uint64_t item) {
  std::seed_seq seq{
      static_cast<uint32_t>(seed),   static_cast<uint32_t>(seed >> 32),
      static_cast<uint32_t>(kernel), static_cast<uint32_t>(leaf + 1),
      static_cast<uint32_t>(item),   static_cast<uint32_t>(item >> 32)};
  return std::mt19937_64(seq);
}

Eigen::Vector3d Gaussian3(std::mt19937_64* rng, double sigma) {
  std::normal_distribution<double> n(0.0, sigma);
  return {n(*rng), n(*rng), n(*rng)};
}

// Median distance from a point to the first image that observes it, over
// at most 10,000 points: the unit of the position noise.
double ViewingDistance(const colmap::Reconstruction& gt) {
  std::vector<double> distances;
  for (const auto& [id, point] : gt.Points3D()) {
    if (distances.size() >= 10000) break;
    const colmap::Image& image =
        gt.Image(point.track.Elements().front().image_id);
    distances.push_back((point.xyz - image.ProjectionCenter()).norm());
  }
  if (distances.empty()) return 1.0;
  std::nth_element(distances.begin(), distances.begin() + distances.size() / 2,
                   distances.end());
  return distances[distances.size() / 2];
}

class TaskModelWriter {
 public:
  TaskModelWriter(const colmap::Reconstruction& gt,
                  const SyntheticTaskResultsOptions& noise)
      : gt_(gt), noise_(noise), distance_(ViewingDistance(gt)) {}

  // The model of task (kernel, leaf): `base` images posed with the kernel
  // model's noise, `own` images with the task's.
  colmap::Reconstruction Model(int kernel, int leaf,
                               const std::vector<colmap::image_t>& base,
                               const std::vector<colmap::image_t>& own) const {
    colmap::Reconstruction model;
    for (const colmap::image_t id : base)
      AddImageWithoutPoints(gt_, id, NoisyPose(kernel, -1, id), &model);
    for (const colmap::image_t id : own)
      AddImageWithoutPoints(gt_, id, NoisyPose(kernel, leaf, id), &model);
    std::unordered_set<colmap::image_t> images(base.begin(), base.end());
    images.insert(own.begin(), own.end());
    std::unordered_set<colmap::point3D_t> points;
    for (const colmap::image_t id : images) {
      for (const colmap::Point2D& p : gt_.Image(id).Points2D())
        if (p.HasPoint3D()) points.insert(p.point3D_id);
    }
    std::vector<colmap::point3D_t> ordered(points.begin(), points.end());
    std::sort(ordered.begin(), ordered.end());
    for (const colmap::point3D_t point_id : ordered) {
      const colmap::Point3D& point = gt_.Point3D(point_id);
      colmap::Track track;
      for (const colmap::TrackElement& el : point.track.Elements())
        if (images.count(el.image_id)) track.AddElement(el);
      if (track.Length() < 2) continue;
      std::mt19937_64 rng = Generator(noise_.seed, kernel, leaf, point_id);
      model.AddPoint3D(
          point.xyz + Gaussian3(&rng, noise_.position_noise * distance_),
          track);
    }
    model.Transform(Frame(kernel, leaf));
    return model;
  }

 private:
  colmap::Rigid3d NoisyPose(int kernel, int leaf, colmap::image_t id) const {
    std::mt19937_64 rng =
        Generator(noise_.seed, kernel, leaf, (uint64_t{1} << 40) + id);
    const colmap::Image& image = gt_.Image(id);
    const Eigen::Vector3d axis = Gaussian3(&rng, 1.0).normalized();
    std::normal_distribution<double> angle(
        0.0, noise_.rotation_noise_deg * kPi / 180);
    const Eigen::Quaterniond rotation =
        (image.CamFromWorld().rotation() *
         Eigen::Quaterniond(Eigen::AngleAxisd(angle(rng), axis)))
            .normalized();
    const Eigen::Vector3d center =
        image.ProjectionCenter() +
        Gaussian3(&rng, noise_.position_noise * distance_);
    return colmap::Rigid3d(rotation, -(rotation * center));
  }

  // The random similarity of a task model's frame.
  colmap::Sim3d Frame(int kernel, int leaf) const {
    std::mt19937_64 rng =
        Generator(noise_.seed, kernel, leaf, uint64_t{1} << 41);
    std::normal_distribution<double> n(0.0, 1.0);
    const Eigen::Quaterniond rotation =
        Eigen::Quaterniond(n(rng), n(rng), n(rng), n(rng)).normalized();
    std::uniform_real_distribution<double> log_scale(-0.7, 0.7);
    return colmap::Sim3d(std::exp(log_scale(rng)), rotation,
                         Gaussian3(&rng, 3 * distance_));
  }

  const colmap::Reconstruction& gt_;
  const SyntheticTaskResultsOptions& noise_;
  const double distance_;
};

bool Fail(const std::string& message, std::string* error) {
  *error = message;
  return false;
}

}  // namespace

void SyntheticTaskResultsOptions::AddTo(OptionTable* t) {
  t->Add("rotation_noise_deg", &rotation_noise_deg,
         "standard deviation of each image's rotation error (degrees)")
      .AtLeast(0);
  t->Add("position_noise", &position_noise,
         "standard deviation of camera and point positions per axis, as a "
         "share of the median viewing distance")
      .AtLeast(0);
  t->Add("seed", &seed, "seed of the noise and of each model's frame");
}

bool SyntheticTaskResultsOptions::Check(std::string* error) const {
  return CheckOptionRows(*this, error);
}

bool WriteTaskResultsFromGroundTruth(
    const TmrMapperOptions& options, const std::string& ground_truth_path,
    const SyntheticTaskResultsOptions& noise, std::string* error,
    const std::function<void(const std::string&)>& progress) {
  if (!noise.Check(error)) return false;
  TmrMapperStages stages(options);
  if (!stages.Load(error)) return false;
  if (!std::filesystem::is_regular_file(
          std::filesystem::path(ground_truth_path) / "images.bin"))
    return Fail("no model in '" + ground_truth_path + "'", error);
  colmap::Reconstruction gt;
  gt.ReadBinary(ground_truth_path);
  const TmrTree& tree = stages.tree();
  for (size_t v = 0; v < tree.image_ids.size(); ++v) {
    const colmap::image_t id = tree.image_ids[v];
    if (!gt.ExistsImage(id) || !gt.Image(id).HasPose() ||
        gt.Image(id).Name() != tree.image_names[v]) {
      return Fail("the ground truth has no posed image " + std::to_string(id) +
                      " named '" + tree.image_names[v] +
                      "' as the database has",
                  error);
    }
  }
  const TaskModelWriter writer(gt, noise);
  int written = 0;
  for (const TmrMapperTask& task : stages.Tasks()) {
    if (task.finished) continue;
    const TmrKernelNode& node = tree.kernels.at(task.kernel);
    const std::vector<colmap::image_t> kernel =
        ImageIdsOf(tree, node.kernel_images);
    std::vector<colmap::image_t> own;
    if (task.leaf >= 0) {
      own = ImageIdsOf(tree, node.leaf_clusters.at(task.leaf));
      for (const colmap::image_t id :
           ImageIdsOf(tree, node.leaf_halos.at(task.leaf)))
        own.push_back(id);
    }
    const colmap::Reconstruction model =
        task.leaf < 0 ? writer.Model(task.kernel, -1, {}, kernel)
                      : writer.Model(task.kernel, task.leaf, kernel, own);
    const std::string path =
        task.leaf < 0 ? stages.work().KernelModel(task.kernel)
                      : stages.work().LeafModel(task.kernel, task.leaf);
    ReconstructionTaskResult result;
    result.success = true;
    result.num_images = static_cast<int>(kernel.size() + own.size());
    result.num_registered = static_cast<int>(model.NumRegImages());
    result.message = "from the ground truth";
    if (!WriteModelAtomically(model, path) ||
        !SaveTaskResult(result, path + ".result"))
      return Fail("cannot write the model of task " + task.id, error);
    ++written;
  }
  if (progress) {
    progress("wrote " + std::to_string(written) +
             " task models from the ground truth");
  }
  return true;
}

}  // namespace tmr
