// Copyright (c) 2026, the tmr authors. BSD-3-Clause.
#include "synthetic/scene_layout.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

namespace tmr {
namespace synthetic {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kCameraHeight = 1.6;
// Radius of the camera ring around a place's building.
constexpr double kRingRadius = 25.0;
// Half-width of streets and link corridors.
constexpr double kStreetHalfWidth = 12.0;

double Uniform(std::mt19937_64& rng, double lo, double hi) {
  return std::uniform_real_distribution<double>(lo, hi)(rng);
}

Eigen::Vector2d Heading(double yaw) { return {std::cos(yaw), std::sin(yaw)}; }

Eigen::Vector3d At(const Eigen::Vector2d& xy, double z) {
  return {xy.x(), xy.y(), z};
}

// One walk of cameras every `spacing` metres from `from` to `to`, heading
// 45 degrees forward-left and forward-right in turn, with jitter.
void AddWalk(const Eigen::Vector2d& from, const Eigen::Vector2d& to,
             double spacing, double start, const std::string& part,
             std::mt19937_64& rng, SceneLayout* layout) {
  const double length = (to - from).norm();
  const Eigen::Vector2d u = (to - from) / length;
  const Eigen::Vector2d w(-u.y(), u.x());
  const double axis_yaw = std::atan2(u.y(), u.x());
  int side = 0;
  for (double s = start; s < length; s += spacing) {
    const Eigen::Vector2d xy = from + s * u + Uniform(rng, -1.5, 1.5) * w;
    const double yaw = axis_yaw + (side++ % 2 ? -kPi / 4 : kPi / 4) +
                       Uniform(rng, -0.15, 0.15);
    layout->cameras.push_back({At(xy, kCameraHeight + Uniform(rng, -0.2, 0.2)),
                               LookRotation(yaw, Uniform(rng, 0.05, 0.2)),
                               part});
  }
}

// Cameras along a corridor: a walk from `from` to `to` and one back, each
// with cameras every `spacing` metres, the second offset by half a spacing.
void AddCorridorCameras(const Eigen::Vector2d& from, const Eigen::Vector2d& to,
                        double spacing, const std::string& part,
                        std::mt19937_64& rng, SceneLayout* layout) {
  if (spacing <= 0 || (to - from).norm() <= 0) return;
  AddWalk(from, to, spacing, spacing / 4, part, rng, layout);
  AddWalk(to, from, spacing, 3 * spacing / 4, part, rng, layout);
}

// Eight cameras at one spot turning full circle (a street corner).
void AddPanorama(const Eigen::Vector2d& center, const std::string& part,
                 std::mt19937_64& rng, SceneLayout* layout) {
  for (int k = 0; k < 8; ++k) {
    const Eigen::Vector2d xy =
        center + Eigen::Vector2d(Uniform(rng, -1, 1), Uniform(rng, -1, 1));
    layout->cameras.push_back(
        {At(xy, kCameraHeight + Uniform(rng, -0.2, 0.2)),
         LookRotation(k * kPi / 4 + Uniform(rng, -0.15, 0.15),
                      Uniform(rng, 0.05, 0.2)),
         part});
  }
}

// Whether `xy` is within `margin` metres of the footprint of a box.
bool NearBox(const Eigen::Vector2d& xy, double margin,
             const std::vector<Box>& boxes) {
  for (const Box& box : boxes) {
    const double c = std::cos(box.yaw), s = std::sin(box.yaw);
    const Eigen::Vector2d d = xy - box.center;
    if (std::abs(c * d.x() + s * d.y()) < box.half_size.x() + margin &&
        std::abs(-s * d.x() + c * d.y()) < box.half_size.y() + margin)
      return true;
  }
  return false;
}

// A building at `center`.
void AddBuilding(const Eigen::Vector2d& center, double yaw,
                 std::mt19937_64& rng, SceneLayout* layout) {
  Box building;
  building.center = center;
  building.yaw = yaw;
  building.half_size = {10.0, 10.0, Uniform(rng, 5.0, 8.0)};
  layout->boxes.push_back(building);
}

// Whether another box than `own` stands between `xy` and `center`.
bool ViewBlocked(const Eigen::Vector2d& xy, const Eigen::Vector2d& center,
                 int own, const std::vector<Box>& boxes) {
  for (int b = 0; b < static_cast<int>(boxes.size()); ++b) {
    if (b != own && boxes[b].Blocks(At(xy, kCameraHeight), At(center, 3.0)))
      return true;
  }
  return false;
}

// A ring of cameras of radius `ring_radius` around `center` (the box `own`),
// looking at it; a position within 2 m of a box, or from which another box
// hides the centre (a close-up of another place's wall that nothing else
// sees), is drawn again.
void AddRing(const Eigen::Vector2d& center, int own, int num_cameras,
             double ring_radius, const std::string& part, std::mt19937_64& rng,
             SceneLayout* layout) {
  for (int k = 0; k < num_cameras; ++k) {
    Eigen::Vector2d xy;
    for (int attempt = 0; attempt < 100; ++attempt) {
      // Near the camera's slot first, then anywhere on the ring (a ring
      // that crosses another place's building has no free slot there).
      const double slot =
          attempt < 20 ? k + Uniform(rng, -0.3, 0.3)
                       : Uniform(rng, 0, static_cast<double>(num_cameras));
      const double angle = 2 * kPi * slot / num_cameras;
      xy = center + (ring_radius + Uniform(rng, -3, 3)) * Heading(angle);
      if (!NearBox(xy, 2.0, layout->boxes) &&
          !ViewBlocked(xy, center, own, layout->boxes))
        break;
    }
    const Eigen::Vector2d to_center = center - xy;
    const double heading =
        std::atan2(to_center.y(), to_center.x()) + Uniform(rng, -0.25, 0.25);
    layout->cameras.push_back({At(xy, kCameraHeight + Uniform(rng, -0.2, 0.2)),
                               LookRotation(heading, Uniform(rng, 0.05, 0.2)),
                               part});
  }
}

// A building at `center` with a ring of cameras of radius `ring_radius`
// looking at it.
void AddPlace(const Eigen::Vector2d& center, double yaw, int num_cameras,
              double ring_radius, const std::string& part, std::mt19937_64& rng,
              SceneLayout* layout) {
  AddBuilding(center, yaw, rng, layout);
  AddRing(center, static_cast<int>(layout->boxes.size()) - 1, num_cameras,
          ring_radius, part, rng, layout);
}

// Facade walls on both sides of a corridor from `from` to `to`.
void AddCorridorWalls(const Eigen::Vector2d& from, const Eigen::Vector2d& to,
                      std::mt19937_64& rng, SceneLayout* layout) {
  const Eigen::Vector2d u = (to - from).normalized();
  const Eigen::Vector2d w(-u.y(), u.x());
  const double yaw = std::atan2(u.y(), u.x());
  const double length = (to - from).norm();
  for (const double side : {1.0, -1.0}) {
    Box wall;
    wall.center = (from + to) / 2 + side * (kStreetHalfWidth + 0.25) * w;
    wall.yaw = yaw;
    wall.half_size = {length / 2, 0.25, Uniform(rng, 3.0, 5.0)};
    wall.textured_faces = side > 0 ? 8 : 4;  // the face towards the axis
    layout->boxes.push_back(wall);
  }
}

void BuildPlaces(const SyntheticSceneOptions& o, std::mt19937_64& rng,
                 SceneLayout* layout) {
  const std::vector<int> cameras = o.PlaceCameras();
  int p = 0;
  double row_y = 0.0;
  for (const int row_length : o.PlaceRows()) {
    double x = 0.0;
    for (int k = 0; k < row_length; ++k, ++p) {
      const double link_length =
          o.place_distance *
          (o.vary_link_lengths ? 1.0 + 0.5 * ((k - 1) % 3) : 1.0);
      if (k > 0) x += link_length;
      const Eigen::Vector2d center(x, row_y);
      AddPlace(center, 0.0, cameras[p], kRingRadius,
               "place" + std::to_string(p), rng, layout);
      if (k == 0 || o.link_spacing <= 0) continue;
      const Eigen::Vector2d from(x - link_length + kRingRadius, row_y);
      const Eigen::Vector2d to(x - kRingRadius, row_y);
      AddCorridorWalls(from, to, rng, layout);
      AddCorridorCameras(
          from, to, o.link_spacing,
          "link" + std::to_string(p - 1) + "-" + std::to_string(p), rng,
          layout);
    }
    // The next row beyond the range of every camera of this one.
    row_y -= 4 * o.place_distance;
  }
  // Unlinked places far off the line, beyond the range of every camera.
  for (int q = 0; q < o.num_unlinked_places; ++q) {
    const Eigen::Vector2d center(q * o.place_distance, 4 * o.place_distance);
    AddPlace(center, Uniform(rng, 0, kPi / 2), o.cameras_per_place, kRingRadius,
             "place" + std::to_string(p + q), rng, layout);
  }
}

// Plazas on a grid (as square as num_places allows), plaza_distance apart,
// each a building with a ring of plaza_radius: the rings overlap, so every
// photo also sees the neighbouring plazas' buildings, and no link photos
// are needed to join them.
void BuildPlazas(const SyntheticSceneOptions& o, std::mt19937_64& rng,
                 SceneLayout* layout) {
  const int columns =
      static_cast<int>(std::ceil(std::sqrt(static_cast<double>(o.num_places))));
  std::vector<Eigen::Vector2d> centers;
  for (int p = 0; p < o.num_places; ++p) {
    centers.emplace_back((p % columns) * o.plaza_distance,
                         (p / columns) * o.plaza_distance);
    AddBuilding(centers.back(), Uniform(rng, 0, kPi / 2), rng, layout);
  }
  for (int p = 0; p < o.num_places; ++p) {
    AddRing(centers[p], p, o.cameras_per_place, o.plaza_radius,
            "plaza" + std::to_string(p), rng, layout);
  }
}

// A row of buildings whose fronts stand at lateral offset `front` from the
// x axis (facing the axis), from x = begin to x = end.
void AddFacadeRow(double begin, double end, double front, std::mt19937_64& rng,
                  SceneLayout* layout) {
  const double side = front > 0 ? 1.0 : -1.0;
  for (double x = begin; x < end;) {
    const double length = std::min(Uniform(rng, 12, 30), end - x);
    if (length > 2.0) {
      Box building;
      building.half_size = {length / 2, 6.0, Uniform(rng, 4.0, 8.0)};
      building.center = {x + length / 2, front + side * 6.0};
      // Textured: the front and both alley sides.
      building.textured_faces = (side > 0 ? 8 : 4) | 1 | 2;
      layout->boxes.push_back(building);
    }
    x += length + Uniform(rng, 0.0, 3.0);
  }
}

void BuildStreet(const SyntheticSceneOptions& o, std::mt19937_64& rng,
                 SceneLayout* layout) {
  const double gap0 = o.gap_begin * o.street_length;
  const double gap1 = o.gap_end * o.street_length;
  const bool removed = o.street_gap == "removed";
  const bool thinned = o.street_gap == "thinned";
  for (const double front : {kStreetHalfWidth, -kStreetHalfWidth}) {
    if (removed) {
      AddFacadeRow(0, gap0, front, rng, layout);
      AddFacadeRow(gap1, o.street_length, front, rng, layout);
    } else {
      AddFacadeRow(0, o.street_length, front, rng, layout);
    }
  }
  const Eigen::Vector2d x_axis(1, 0);
  if (!removed && !thinned) {
    AddCorridorCameras({0, 0}, o.street_length * x_axis, o.camera_spacing,
                       "street", rng, layout);
    return;
  }
  AddCorridorCameras({0, 0}, gap0 * x_axis, o.camera_spacing, "street", rng,
                     layout);
  if (thinned) {
    AddCorridorCameras(gap0 * x_axis, gap1 * x_axis,
                       o.camera_spacing * o.gap_thinning, "gap", rng, layout);
  }
  AddCorridorCameras(gap1 * x_axis, o.street_length * x_axis, o.camera_spacing,
                     "street", rng, layout);
}

void BuildCity(const SyntheticSceneOptions& o, std::mt19937_64& rng,
               SceneLayout* layout) {
  constexpr double kBlock = 40.0;
  constexpr double kStreet = 2 * kStreetHalfWidth;
  constexpr double kPitch = kBlock + kStreet;
  // A ring of blocks outside the outermost streets gives them facades too.
  for (int bx = -1; bx <= o.city_blocks_x; ++bx) {
    for (int by = -1; by <= o.city_blocks_y; ++by) {
      Box block;
      block.center = {kStreet + bx * kPitch + kBlock / 2,
                      kStreet + by * kPitch + kBlock / 2};
      block.half_size = {kBlock / 2 - 1, kBlock / 2 - 1, Uniform(rng, 5, 12)};
      layout->boxes.push_back(block);
    }
  }
  // Streets between the corners, panoramas at the corners.
  for (int i = 0; i <= o.city_blocks_x; ++i) {
    for (int j = 0; j <= o.city_blocks_y; ++j) {
      const Eigen::Vector2d corner(kStreetHalfWidth + i * kPitch,
                                   kStreetHalfWidth + j * kPitch);
      AddPanorama(corner, "city", rng, layout);
      const Eigen::Vector2d margin(kStreetHalfWidth, 0);
      if (i < o.city_blocks_x) {
        AddCorridorCameras(corner + margin,
                           corner + Eigen::Vector2d(kPitch, 0) - margin,
                           o.camera_spacing, "city", rng, layout);
      }
      if (j < o.city_blocks_y) {
        const Eigen::Vector2d up(0, kStreetHalfWidth);
        AddCorridorCameras(corner + up,
                           corner + Eigen::Vector2d(0, kPitch) - up,
                           o.camera_spacing, "city", rng, layout);
      }
    }
  }
}

}  // namespace

bool Box::Blocks(const Eigen::Vector3d& from, const Eigen::Vector3d& to) const {
  // Slab test in the box's local frame, centre at half height.
  const double c = std::cos(yaw), s = std::sin(yaw);
  auto local = [&](const Eigen::Vector3d& p) {
    const double dx = p.x() - center.x(), dy = p.y() - center.y();
    return Eigen::Vector3d(c * dx + s * dy, -s * dx + c * dy,
                           p.z() - half_size.z());
  };
  const Eigen::Vector3d p0 = local(from);
  const Eigen::Vector3d d = local(to) - p0;
  double t0 = 1e-6, t1 = 1.0 - 1e-6;
  for (int k = 0; k < 3; ++k) {
    if (std::abs(d[k]) < 1e-12) {
      if (std::abs(p0[k]) > half_size[k]) return false;
      continue;
    }
    double a = (-half_size[k] - p0[k]) / d[k];
    double b = (half_size[k] - p0[k]) / d[k];
    if (a > b) std::swap(a, b);
    t0 = std::max(t0, a);
    t1 = std::min(t1, b);
    if (t0 > t1) return false;
  }
  return true;
}

Eigen::Matrix3d LookRotation(double yaw, double pitch) {
  const Eigen::Vector3d forward(std::cos(pitch) * std::cos(yaw),
                                std::cos(pitch) * std::sin(yaw),
                                std::sin(pitch));
  const Eigen::Vector3d right =
      forward.cross(Eigen::Vector3d::UnitZ()).normalized();
  const Eigen::Vector3d down = forward.cross(right);
  Eigen::Matrix3d rotation;
  rotation.row(0) = right;
  rotation.row(1) = down;
  rotation.row(2) = forward;
  return rotation;
}

SceneLayout BuildSceneLayout(const SyntheticSceneOptions& options,
                             std::mt19937_64& rng) {
  SceneLayout layout;
  if (options.family == "places") {
    BuildPlaces(options, rng, &layout);
  } else if (options.family == "plazas") {
    BuildPlazas(options, rng, &layout);
  } else if (options.family == "street") {
    BuildStreet(options, rng, &layout);
  } else {
    BuildCity(options, rng, &layout);
  }
  return layout;
}

std::vector<ScenePoint> SampleScenePoints(const std::vector<Box>& boxes,
                                          double density, double relief,
                                          std::mt19937_64& rng) {
  std::vector<ScenePoint> points;
  for (int b = 0; b < static_cast<int>(boxes.size()); ++b) {
    const Box& box = boxes[b];
    const double c = std::cos(box.yaw), s = std::sin(box.yaw);
    const Eigen::Vector3d ax(c, s, 0), ay(-s, c, 0);
    const Eigen::Vector3d center(box.center.x(), box.center.y(), 0);
    const double height = 2 * box.half_size.z();
    // Face k: outward normal, the axis along it, half width along it.
    const struct {
      Eigen::Vector3d normal, along;
      double offset, half_width;
    } faces[4] = {{ax, ay, box.half_size.x(), box.half_size.y()},
                  {-ax, ay, box.half_size.x(), box.half_size.y()},
                  {ay, ax, box.half_size.y(), box.half_size.x()},
                  {-ay, ax, box.half_size.y(), box.half_size.x()}};
    for (int k = 0; k < 4; ++k) {
      if (!(box.textured_faces & (1 << k))) continue;
      const auto& f = faces[k];
      const double area = 2 * f.half_width * (height - 0.3);
      const int count = std::poisson_distribution<int>(density * area)(rng);
      for (int i = 0; i < count; ++i) {
        const Eigen::Vector3d xyz =
            center + f.offset * f.normal +
            Uniform(rng, -f.half_width, f.half_width) * f.along +
            Eigen::Vector3d(0, 0, Uniform(rng, 0.3, height));
        const double depth = relief > 0 ? Uniform(rng, -relief, relief) : 0.0;
        points.push_back({xyz + depth * f.normal, f.normal, b});
      }
    }
  }
  return points;
}

}  // namespace synthetic
}  // namespace tmr
