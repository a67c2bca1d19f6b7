// Copyright (c) 2026, the tmr authors. BSD-3-Clause.
#include "synthetic/observations.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <random>
#include <unordered_map>

namespace tmr {
namespace synthetic {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kCellSize = 10.0;

uint64_t SplitMix(uint64_t x) {
  x += 0x9e3779b97f4a7c15ULL;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ULL;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebULL;
  return x ^ (x >> 31);
}

uint64_t PairKey(int a, int b) {
  return (static_cast<uint64_t>(std::min(a, b)) << 32) |
         static_cast<uint32_t>(std::max(a, b));
}

// Points bucketed in a horizontal grid for range queries.
class PointGrid {
 public:
  explicit PointGrid(const std::vector<ScenePoint>& points) {
    for (int i = 0; i < static_cast<int>(points.size()); ++i) {
      cells_[Key(Cell(points[i].xyz.x()), Cell(points[i].xyz.y()))].push_back(
          i);
    }
  }
  template <typename F>
  void ForEachNear(const Eigen::Vector3d& center, double range, F&& f) const {
    const int x0 = Cell(center.x() - range), x1 = Cell(center.x() + range);
    const int y0 = Cell(center.y() - range), y1 = Cell(center.y() + range);
    for (int x = x0; x <= x1; ++x) {
      for (int y = y0; y <= y1; ++y) {
        const auto it = cells_.find(Key(x, y));
        if (it == cells_.end()) continue;
        for (const int i : it->second) f(i);
      }
    }
  }

 private:
  static int Cell(double v) {
    return static_cast<int>(std::floor(v / kCellSize));
  }
  static int64_t Key(int x, int y) {
    // Two's-complement bits of x and y side by side (shifting a negative
    // int64_t is undefined behaviour; UBSan found it).
    return static_cast<int64_t>(
        (static_cast<uint64_t>(static_cast<uint32_t>(x)) << 32) |
        static_cast<uint32_t>(y));
  }
  std::unordered_map<int64_t, std::vector<int>> cells_;
};

// One detection of a scene point: image, keypoint, viewing ray and distance.
struct Detection {
  int image;
  uint32_t keypoint;
  Eigen::Vector3f ray;  // unit vector from the point to the camera
  float distance;
};

std::vector<std::vector<Detection>> DetectionsByPoint(
    const SceneLayout& layout, const std::vector<ScenePoint>& points,
    const std::vector<ImageKeypoints>& keypoints) {
  std::vector<std::vector<Detection>> detections(points.size());
  for (int image = 0; image < static_cast<int>(keypoints.size()); ++image) {
    const Eigen::Vector3d& center = layout.cameras[image].center;
    for (uint32_t k = 0; k < keypoints[image].point.size(); ++k) {
      const int p = keypoints[image].point[k];
      if (p < 0) continue;
      const Eigen::Vector3d ray = center - points[p].xyz;
      const double distance = ray.norm();
      detections[p].push_back({image, k, (ray / distance).cast<float>(),
                               static_cast<float>(distance)});
    }
  }
  return detections;
}

// Calls f(image_a, image_b, detection_a, detection_b) for every pair of
// detections of a point that match.
template <typename F>
void ForEachMatch(const std::vector<std::vector<Detection>>& detections,
                  const SyntheticSceneOptions& options, F&& f) {
  const float min_cos = std::cos(options.max_match_angle_deg * kPi / 180);
  const float max_ratio = options.max_scale_ratio;
  const double falloff = options.match_angle_falloff_deg * kPi / 180;
  for (size_t p = 0; p < detections.size(); ++p) {
    const auto& d = detections[p];
    for (size_t a = 0; a < d.size(); ++a) {
      for (size_t b = a + 1; b < d.size(); ++b) {
        const float cos_angle = d[a].ray.dot(d[b].ray);
        if (cos_angle < min_cos) continue;
        const float ratio = d[a].distance / d[b].distance;
        if (ratio > max_ratio || ratio * max_ratio < 1) continue;
        const double angle = std::acos(std::min(1.0f, cos_angle)) / falloff;
        if (HashUniform(options.seed, p, d[a].image, d[b].image) >=
            options.match_probability * std::exp(-0.5 * angle * angle)) {
          continue;
        }
        f(d[a], d[b]);
      }
    }
  }
}

}  // namespace

double HashUniform(uint64_t seed, uint64_t a, uint64_t b, uint64_t c) {
  const uint64_t h = SplitMix(SplitMix(SplitMix(seed ^ a) ^ b) ^ c);
  return (h >> 11) * (1.0 / 9007199254740992.0);
}

std::vector<ImageKeypoints> DetectKeypoints(
    const SceneLayout& layout, const std::vector<ScenePoint>& points,
    const std::vector<ImageIntrinsics>& intrinsics,
    const SyntheticSceneOptions& options) {
  const PointGrid grid(points);
  const double min_facing = std::cos(options.max_view_angle_deg * kPi / 180);
  const double range2 = options.max_range * options.max_range;
  std::vector<ImageKeypoints> result(layout.cameras.size());
  for (size_t i = 0; i < layout.cameras.size(); ++i) {
    const SceneCamera& camera = layout.cameras[i];
    const ImageIntrinsics& k = intrinsics[i];
    std::mt19937_64 rng(SplitMix(options.seed ^ SplitMix(i + 1)));
    std::normal_distribution<double> noise(0.0, options.keypoint_noise_px);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    // Boxes that may hide something from this camera, with the distance
    // below which they cannot hide anything.
    std::vector<std::pair<int, double>> near_boxes;
    for (int b = 0; b < static_cast<int>(layout.boxes.size()); ++b) {
      const Box& box = layout.boxes[b];
      const double reach = box.half_size.head<2>().norm();
      const double distance =
          (box.center - camera.center.head<2>()).norm() - reach;
      if (distance < options.max_range) {
        near_boxes.emplace_back(b, std::max(0.0, distance));
      }
    }
    ImageKeypoints& out = result[i];
    grid.ForEachNear(camera.center, options.max_range, [&](int p) {
      const ScenePoint& point = points[p];
      const Eigen::Vector3d to_camera = camera.center - point.xyz;
      const double distance2 = to_camera.squaredNorm();
      if (distance2 > range2) return;
      const Eigen::Vector3d in_camera = camera.cam_from_world * -to_camera;
      if (in_camera.z() < 0.5) return;
      const Eigen::Vector2d xy(
          k.focal_px * in_camera.x() / in_camera.z() + k.width / 2.0,
          k.focal_px * in_camera.y() / in_camera.z() + k.height / 2.0);
      if (xy.x() < 0 || xy.y() < 0 || xy.x() >= k.width || xy.y() >= k.height) {
        return;
      }
      const double distance = std::sqrt(distance2);
      if (point.normal.dot(to_camera) < min_facing * distance) return;
      for (const auto& [b, min_distance] : near_boxes) {
        if (b == point.box || min_distance > distance) continue;
        if (layout.boxes[b].Blocks(camera.center, point.xyz)) return;
      }
      if (HashUniform(options.seed, p, i, 0x5eed) >=
          options.detection_probability) {
        return;
      }
      const Eigen::Vector2d noisy =
          xy + Eigen::Vector2d(noise(rng), noise(rng));
      if (noisy.x() < 0 || noisy.y() < 0 || noisy.x() >= k.width ||
          noisy.y() >= k.height) {
        return;
      }
      out.xy.push_back(noisy);
      out.point.push_back(p);
    });
    const int num_unmatched = static_cast<int>(
        std::lround(options.unmatched_keypoint_ratio * out.xy.size()));
    for (int u = 0; u < num_unmatched; ++u) {
      out.xy.emplace_back(unit(rng) * k.width, unit(rng) * k.height);
      out.point.push_back(-1);
    }
    // Shuffle so that keypoint order says nothing about matches.
    std::vector<int> order(out.xy.size());
    for (size_t j = 0; j < order.size(); ++j) order[j] = j;
    std::shuffle(order.begin(), order.end(), rng);
    ImageKeypoints shuffled;
    shuffled.xy.reserve(order.size());
    shuffled.point.reserve(order.size());
    for (const int j : order) {
      shuffled.xy.push_back(out.xy[j]);
      shuffled.point.push_back(out.point[j]);
    }
    out = std::move(shuffled);
  }
  return result;
}

std::vector<ImagePairMatches> MatchKeypoints(
    const SceneLayout& layout, const std::vector<ScenePoint>& points,
    const std::vector<ImageKeypoints>& keypoints,
    const SyntheticSceneOptions& options) {
  const int num_images = static_cast<int>(keypoints.size());
  const auto detections = DetectionsByPoint(layout, points, keypoints);

  // Pass 1: number of matches of every overlapping pair.
  std::unordered_map<uint64_t, int> counts;
  ForEachMatch(detections, options,
               [&](const Detection& a, const Detection& b) {
                 ++counts[PairKey(a.image, b.image)];
               });

  // Image retrieval: each image keeps its best partners; a pair is matched
  // when either image retrieves the other.
  std::vector<std::vector<std::pair<int, int>>> partners(num_images);
  for (const auto& [key, count] : counts) {
    if (count < options.min_num_inliers) continue;
    const int a = key >> 32, b = key & 0xffffffffu;
    partners[a].emplace_back(count, b);
    partners[b].emplace_back(count, a);
  }
  std::map<uint64_t, int> selected;  // pair key -> index in result
  for (int a = 0; a < num_images; ++a) {
    auto& list = partners[a];
    std::sort(list.begin(), list.end(), [](const auto& x, const auto& y) {
      return x.first != y.first ? x.first > y.first : x.second < y.second;
    });
    const size_t keep =
        options.max_pairs_per_image > 0
            ? std::min<size_t>(list.size(), options.max_pairs_per_image)
            : list.size();
    for (size_t j = 0; j < keep; ++j) selected[PairKey(a, list[j].second)] = 0;
  }
  std::vector<ImagePairMatches> result;
  result.reserve(selected.size());
  for (auto& [key, index] : selected) {
    index = static_cast<int>(result.size());
    result.push_back({static_cast<int>(key >> 32),
                      static_cast<int>(key & 0xffffffffu),
                      {},
                      false});
  }

  // Pass 2: the matches of the selected pairs (same decisions as pass 1).
  ForEachMatch(detections, options,
               [&](const Detection& a, const Detection& b) {
                 const auto it = selected.find(PairKey(a.image, b.image));
                 if (it == selected.end()) return;
                 ImagePairMatches& pair = result[it->second];
                 if (a.image == pair.image1) {
                   pair.inliers.push_back({a.keypoint, b.keypoint});
                 } else {
                   pair.inliers.push_back({b.keypoint, a.keypoint});
                 }
               });

  // False verified pairs between images that share no point.
  std::mt19937_64 rng(SplitMix(options.seed ^ 0xfa15e));
  const int num_false = static_cast<int>(
      std::lround(options.false_pairs_per_100_images * num_images / 100.0));
  std::uniform_int_distribution<int> any_image(0, std::max(0, num_images - 1));
  for (int f = 0, attempts = 0; f < num_false && attempts < 100 * num_false;
       ++attempts) {
    const int a = any_image(rng), b = any_image(rng);
    if (a == b || counts.count(PairKey(a, b)) ||
        selected.count(PairKey(a, b))) {
      continue;
    }
    const int n1 = keypoints[std::min(a, b)].xy.size();
    const int n2 = keypoints[std::max(a, b)].xy.size();
    const int num_inliers = std::uniform_int_distribution<int>(15, 40)(rng);
    if (n1 < num_inliers || n2 < num_inliers) continue;
    ImagePairMatches pair{std::min(a, b), std::max(a, b), {}, true};
    std::vector<uint32_t> k1(n1), k2(n2);
    for (int j = 0; j < n1; ++j) k1[j] = j;
    for (int j = 0; j < n2; ++j) k2[j] = j;
    std::shuffle(k1.begin(), k1.end(), rng);
    std::shuffle(k2.begin(), k2.end(), rng);
    for (int j = 0; j < num_inliers; ++j)
      pair.inliers.push_back({k1[j], k2[j]});
    selected[PairKey(a, b)] = static_cast<int>(result.size());
    result.push_back(std::move(pair));
    ++f;
  }
  std::sort(result.begin(), result.end(), [](const auto& x, const auto& y) {
    return std::tie(x.image1, x.image2) < std::tie(y.image1, y.image2);
  });
  return result;
}

}  // namespace synthetic
}  // namespace tmr
