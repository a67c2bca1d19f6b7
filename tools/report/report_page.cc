// Copyright (c) 2026, the tmr authors. BSD-3-Clause.
#include "report/report_page.h"

#include <colmap/scene/reconstruction.h>
#include <colmap/scene/reconstruction_io_binary.h>
#include <colmap/util/endian.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <stdexcept>
#include <vector>

#include "drawing/force_layout.h"
#include "tmr/io/atomic_file.h"
#include "tmr/partition/tmr_tree.h"

namespace tmr {

// The page's template, style and script (tools/report/page/), embedded at
// build time by cmake/embed_text_files.cmake.
extern const char* const kReportPageTemplate;
extern const char* const kReportPageStyle;
extern const char* const kReportPageScript_common;
extern const char* const kReportPageScript_models;
extern const char* const kReportPageScript_partition;
extern const char* const kReportPageScript_timeline;
extern const char* const kReportPageScript_merges;
extern const char* const kReportPageScript_main;

namespace {

namespace fs = std::filesystem;
using Json = nlohmann::json;

// Coordinates on an integer grid (x = origin + q * step), so that the page
// stays small: the step is a 10,000th of the span that holds 96% of the
// values on each axis.
struct Grid {
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();
  double step = 1.0;

  Json Quantized(const Eigen::Vector3d& x) const {
    const Eigen::Vector3d q = (x - origin) / step;
    return {std::llround(q.x()), std::llround(q.y()), std::llround(q.z())};
  }
};

Grid GridOf(std::vector<Eigen::Vector3d> xyz) {
  Grid grid;
  if (xyz.empty()) return grid;
  double span = 0.0;
  for (int axis = 0; axis < 3; ++axis) {
    std::vector<double> values;
    for (const Eigen::Vector3d& x : xyz) values.push_back(x(axis));
    std::sort(values.begin(), values.end());
    const double low = values[values.size() * 2 / 100];
    const double high = values[values.size() * 98 / 100];
    grid.origin(axis) = low;
    span = std::max(span, high - low);
  }
  grid.step = std::max(span / 10000.0, 1e-12);
  return grid;
}

void AppendAll(const Json& values, Json* out) {
  for (const Json& v : values) out->push_back(v);
}

// What the page draws of one model, streamed from its binary files so that
// the page never holds a whole model (at 9,768 photos a whole model took
// 2.4 GB, more than the join that wrote it): its figures, its cameras
// (centre, then the viewing direction and the image's right and down
// half-extents at unit depth) by image id, and every `stride`-th of its
// points with colours, in the file's order.
struct ModelContents {
  Json figures;
  std::vector<Eigen::Vector3d> centres;
  std::vector<std::array<Eigen::Vector3d, 3>> camera_axes;
  std::vector<Eigen::Vector3d> points;
  std::vector<Eigen::Matrix<uint8_t, 3, 1>> colours;
};

template <typename T>
T Read(std::istream* stream) {
  return colmap::ReadBinaryLittleEndian<T>(stream);
}

std::ifstream OpenModelFile(const fs::path& path) {
  std::ifstream file(path, std::ios::binary);
  if (!file) {
    throw std::runtime_error("cannot read '" + path.string() +
                             "' (the report reads binary COLMAP models)");
  }
  return file;
}

// The number of 3D points of a binary model (points3D.bin's first field).
size_t NumPointsOfModel(const fs::path& model) {
  std::ifstream file = OpenModelFile(model / "points3D.bin");
  return Read<uint64_t>(&file);
}

ModelContents ReadModelContents(const fs::path& path, const std::string& name,
                                size_t stride) {
  colmap::Reconstruction cameras;  // only the cameras: small
  colmap::ReadCamerasBinary(cameras, path / "cameras.bin");
  ModelContents contents;
  // images.bin: the registered images, each with its pose and keypoints.
  std::ifstream images = OpenModelFile(path / "images.bin");
  const uint64_t num_images = Read<uint64_t>(&images);
  // By image id: the centre and the axes.
  std::map<colmap::image_t,
           std::pair<Eigen::Vector3d, std::array<Eigen::Vector3d, 3>>>
      by_id;
  for (uint64_t i = 0; i < num_images && images; ++i) {
    const colmap::image_t id = Read<colmap::image_t>(&images);
    Eigen::Quaterniond rotation;
    rotation.w() = Read<double>(&images);
    rotation.x() = Read<double>(&images);
    rotation.y() = Read<double>(&images);
    rotation.z() = Read<double>(&images);
    Eigen::Vector3d translation;
    for (int k = 0; k < 3; ++k) translation(k) = Read<double>(&images);
    const colmap::Camera& camera =
        cameras.Camera(Read<colmap::camera_t>(&images));
    images.ignore(std::numeric_limits<std::streamsize>::max(), '\0');
    const uint64_t num_points2D = Read<uint64_t>(&images);
    images.seekg(
        num_points2D * (2 * sizeof(double) + sizeof(colmap::point3D_t)),
        std::ios::cur);
    const Eigen::Matrix3d r = rotation.normalized().toRotationMatrix();
    const double f = std::max(camera.MeanFocalLength(), 1e-9);
    by_id[id] = {
        -r.transpose() * translation,
        {r.row(2).transpose(), r.row(0).transpose() * camera.width / (2 * f),
         r.row(1).transpose() * camera.height / (2 * f)}};
  }
  if (!images)
    throw std::runtime_error("'" + path.string() + "/images.bin' is cut short");
  for (const auto& [id, camera] : by_id) {
    contents.centres.push_back(camera.first);
    contents.camera_axes.push_back(camera.second);
  }
  // points3D.bin: every point's position, colour, error and track.
  std::ifstream points = OpenModelFile(path / "points3D.bin");
  const uint64_t num_points = Read<uint64_t>(&points);
  uint64_t num_observations = 0, num_errors = 0;
  double error_sum = 0.0;
  for (uint64_t p = 0; p < num_points && points; ++p) {
    Read<colmap::point3D_t>(&points);
    Eigen::Vector3d xyz;
    for (int k = 0; k < 3; ++k) xyz(k) = Read<double>(&points);
    Eigen::Matrix<uint8_t, 3, 1> colour;
    for (int k = 0; k < 3; ++k) colour(k) = Read<uint8_t>(&points);
    const double error = Read<double>(&points);
    if (error != -1.0) {  // as colmap::Point3D::HasError
      error_sum += error;
      ++num_errors;
    }
    const uint64_t track_length = Read<uint64_t>(&points);
    num_observations += track_length;
    points.seekg(
        track_length * (sizeof(colmap::image_t) + sizeof(colmap::point2D_t)),
        std::ios::cur);
    if (p % std::max<size_t>(stride, 1) != 0) continue;
    contents.points.push_back(xyz);
    contents.colours.push_back(colour);
  }
  if (!points)
    throw std::runtime_error("'" + path.string() +
                             "/points3D.bin' is cut short");
  // As colmap::Reconstruction's figures.
  contents.figures = {{"name", name},
                      {"registered", num_images},
                      {"points", num_points},
                      {"observations", num_observations},
                      {"mean_reprojection_error_px",
                       num_errors == 0 ? 0.0 : error_sum / num_errors}};
  return contents;
}

// One model's data: its figures, its cameras (on the grid, then the axes
// in thousandths) and its drawn points with colours.
Json ModelData(const ModelContents& contents) {
  std::vector<Eigen::Vector3d> drawn = contents.centres;
  drawn.insert(drawn.end(), contents.points.begin(), contents.points.end());
  const Grid grid = GridOf(drawn);
  Json cameras = Json::array(), xyz = Json::array(), rgb = Json::array();
  for (size_t c = 0; c < contents.centres.size(); ++c) {
    AppendAll(grid.Quantized(contents.centres[c]), &cameras);
    for (const Eigen::Vector3d& axis : contents.camera_axes[c])
      for (int k = 0; k < 3; ++k)
        cameras.push_back(std::lround(1000 * axis(k)));
  }
  for (size_t i = 0; i < contents.points.size(); ++i) {
    AppendAll(grid.Quantized(contents.points[i]), &xyz);
    for (int k = 0; k < 3; ++k) rgb.push_back(int(contents.colours[i](k)));
  }
  Json data = contents.figures;
  data["origin"] = {grid.origin.x(), grid.origin.y(), grid.origin.z()};
  data["step"] = grid.step;
  data["cameras"] = std::move(cameras);
  data["points_drawn"] = contents.points.size();
  data["xyz"] = std::move(xyz);
  data["rgb"] = std::move(rgb);
  return data;
}

// The run's models output_path/0, 1, ..., in order, each streamed once,
// their drawn points shared out by size.
Json ModelsData(const std::string& output_path,
                const ReportPageOptions& options) {
  std::vector<fs::path> paths;
  std::vector<size_t> num_points;
  size_t total = 0;
  for (int i = 0;; ++i) {
    const fs::path path = fs::path(output_path) / std::to_string(i);
    if (!fs::is_directory(path)) break;
    paths.push_back(path);
    num_points.push_back(NumPointsOfModel(path));
    total += num_points.back();
  }
  Json models = Json::array();
  for (size_t m = 0; m < paths.size(); ++m) {
    const double quota = total == 0 ? 0.0
                                    : double(options.max_drawn_points) *
                                          double(num_points[m]) / double(total);
    const size_t stride = quota <= 0 ? num_points[m] + 1
                                     : size_t(std::ceil(num_points[m] / quota));
    models.push_back(
        ModelData(ReadModelContents(paths[m], std::to_string(m), stride)));
  }
  return models;
}

Json KernelsData(const TmrTree& tree) {
  Json kernels = Json::array();
  for (const TmrKernelNode& k : tree.kernels) {
    Json leaves = Json::array();
    for (const auto& leaf : k.leaf_clusters) leaves.push_back(leaf.size());
    kernels.push_back({{"exemplar", tree.image_names.at(k.exemplar)},
                       {"kernel_images", k.kernel_images.size()},
                       {"cluster_images", k.cluster_images.size()},
                       {"leaves", std::move(leaves)}});
  }
  return kernels;
}

// The map: each image's place (on a 0..10,000 grid), kernel and leaf
// cluster (-1: a kernel image; kernel -1: unclustered), the exemplars, and
// the similarity graph's edges as (u, v, Jaccard weight in thousandths).
Json MapData(const PartitionMap& map) {
  const size_t n = map.layout.size();
  std::vector<int> kernel(n, -1), leaf(n, -1);
  Json exemplars = Json::array();
  for (size_t k = 0; k < map.tree.kernels.size(); ++k) {
    const TmrKernelNode& node = map.tree.kernels[k];
    for (size_t l = 0; l < node.leaf_clusters.size(); ++l)
      for (const int v : node.leaf_clusters[l]) kernel[v] = k, leaf[v] = l;
    for (const int v : node.kernel_images) kernel[v] = k, leaf[v] = -1;
    exemplars.push_back(node.exemplar);
  }
  Json xy = Json::array(), edges = Json::array();
  for (const auto& p : LayoutInUnitSquare(map.layout)) {
    xy.push_back(std::lround(p[0] * 10000));
    xy.push_back(std::lround(p[1] * 10000));
  }
  for (const WeightedEdge& e : map.similarity.Edges()) {
    edges.push_back(e.u);
    edges.push_back(e.v);
    edges.push_back(std::lround(1000 * e.weight));
  }
  return {{"names", map.tree.image_names},
          {"xy", std::move(xy)},
          {"kernel", kernel},
          {"leaf", leaf},
          {"exemplars", std::move(exemplars)},
          {"edges", std::move(edges)}};
}

Json ReadJsonFile(const std::string& path) {
  std::ifstream file(path);
  if (!file) throw std::runtime_error("cannot read '" + path + "'");
  try {
    return Json::parse(file);
  } catch (const Json::exception& e) {
    throw std::runtime_error("'" + path + "' is not JSON: " + e.what());
  }
}

// Replaces the first `marker` in `text` by `value`.
void Fill(const std::string& marker, const std::string& value,
          std::string* text) {
  const size_t at = text->find(marker);
  if (at == std::string::npos)
    throw std::logic_error("report page template has no " + marker);
  text->replace(at, marker.size(), value);
}

}  // namespace

std::string ReportPageData(const std::string& output_path,
                           const PartitionMap* map,
                           const ReportPageOptions& options) {
  if (!options.Check()) throw std::invalid_argument("bad ReportPageOptions");
  Json data;
  data["run"] = ReadJsonFile((fs::path(output_path) / "report.json").string());
  if (map) {
    data["kernels"] = KernelsData(map->tree);
    data["unclustered"] = map->tree.unclustered.size();
    data["map"] = MapData(*map);
  } else {
    std::ifstream tree_file(TmrTreeJsonPath(output_path));
    const TmrTree tree = ReadTmrTreeJson(tree_file);
    data["kernels"] = KernelsData(tree);
    data["unclustered"] = tree.unclustered.size();
    data["map"] = nullptr;
  }
  data["max_drawn_points"] = options.max_drawn_points;
  data["models"] = ModelsData(output_path, options);
  const fs::path evaluation = fs::path(output_path) / "eval.json";
  data["evaluation"] = fs::is_regular_file(evaluation)
                           ? ReadJsonFile(evaluation.string())
                           : Json(nullptr);
  return data.dump();
}

std::string ReportPageHtml(const std::string& data) {
  // "</" only occurs inside JSON strings, where "<\/" reads the same; the
  // script element then cannot be closed early.
  std::string safe;
  safe.reserve(data.size());
  for (size_t i = 0; i < data.size(); ++i) {
    safe += data[i];
    if (data[i] == '<' && i + 1 < data.size() && data[i + 1] == '/')
      safe += '\\';
  }
  // The data last: its text (image names) may hold anything.
  std::string page = kReportPageTemplate;
  Fill("/*TMR_STYLE*/", kReportPageStyle, &page);
  // The helpers, each section, then the script that draws them.
  std::string script;
  for (const char* part :
       {kReportPageScript_common, kReportPageScript_models,
        kReportPageScript_partition, kReportPageScript_timeline,
        kReportPageScript_merges, kReportPageScript_main})
    script += part;
  Fill("/*TMR_SCRIPT*/", script, &page);
  Fill("/*TMR_DATA*/", safe, &page);
  return page;
}

void WriteRunPictures(const std::string& database_path,
                      const MatchGraphOptions& match_graph,
                      const std::string& output_path,
                      const std::function<void(const std::string&)>& progress,
                      const ReportPageOptions& options) {
  const std::optional<PartitionMap> map = ReadRunPartitionMap(
      database_path, match_graph, output_path, options.max_map_images);
  if (map) {
    DrawPartitionPicture(*map,
                         (fs::path(output_path) / "partition.png").string());
  } else if (progress) {
    progress("partition.png and the report's map skipped: more than " +
             std::to_string(options.max_map_images) + " images to draw");
  }
  const std::string page_path =
      (fs::path(output_path) / "report.html").string();
  const std::string page = ReportPageHtml(
      ReportPageData(output_path, map ? &*map : nullptr, options));
  if (!WriteFileAtomically(page_path, page))
    throw std::runtime_error("cannot write '" + page_path + "'");
  if (progress) {
    char size[32];
    std::snprintf(size, sizeof(size), "%.1f MB", page.size() / 1048576.0);
    progress("report.html written (" + std::string(size) +
             "; open it in a browser)");
  }
}

}  // namespace tmr
