// Copyright (c) 2026, the tmr authors. BSD-3-Clause.
#include "drawing/partition_picture.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "drawing/force_layout.h"

namespace tmr {
namespace {

cv::Scalar Colour(int cluster, int leaf, int num_leaves) {
  const int hue = (cluster * 47) % 180;  // OpenCV hue range
  const int value =
      num_leaves > 1 ? 140 + (115 * leaf) / (num_leaves - 1) : 220;
  cv::Mat hsv(1, 1, CV_8UC3, cv::Scalar(hue, 200, value)), bgr;
  cv::cvtColor(hsv, bgr, cv::COLOR_HSV2BGR);
  const cv::Vec3b c = bgr.at<cv::Vec3b>(0, 0);
  return {double(c[0]), double(c[1]), double(c[2])};
}

}  // namespace

bool DrawPartitionPicture(const ImageGraph& similarity, const TmrTree& tree,
                          const std::string& png_path, int size_px) {
  PartitionMap map{similarity, tree, ForceDirectedLayout(similarity)};
  return DrawPartitionPicture(map, png_path, size_px);
}

bool DrawPartitionPicture(const PartitionMap& map, const std::string& png_path,
                          int size_px) {
  const ImageGraph& similarity = map.similarity;
  const TmrTree& tree = map.tree;
  const int n = similarity.NumVertices();
  if (n == 0) return false;
  const std::vector<std::array<double, 2>> unit =
      LayoutInUnitSquare(map.layout);
  const double margin = 40;
  auto pixel = [&](int v) {
    return cv::Point(
        static_cast<int>(margin + unit[v][0] * (size_px - 2 * margin)),
        static_cast<int>(margin + unit[v][1] * (size_px - 2 * margin)));
  };
  cv::Mat canvas(size_px, size_px, CV_8UC3, cv::Scalar(255, 255, 255));
  for (const WeightedEdge& e : similarity.Edges()) {
    const int shade =
        235 - static_cast<int>(120 * std::min(1.0, e.weight / 0.3));
    cv::line(canvas, pixel(e.u), pixel(e.v), cv::Scalar(shade, shade, shade), 1,
             cv::LINE_AA);
  }
  const int radius =
      std::max(3, std::min(8, static_cast<int>(size_px / std::sqrt(4.0 * n))));
  for (size_t k = 0; k < tree.kernels.size(); ++k) {
    const TmrKernelNode& node = tree.kernels[k];
    const int num_leaves = static_cast<int>(node.leaf_clusters.size());
    for (int l = 0; l < num_leaves; ++l) {
      for (const int v : node.leaf_clusters[l]) {
        cv::circle(canvas, pixel(v), radius, Colour(k, l, num_leaves),
                   cv::FILLED, cv::LINE_AA);
      }
    }
    for (const int v : node.kernel_images) {
      cv::circle(canvas, pixel(v), radius, Colour(k, 0, 1), cv::FILLED,
                 cv::LINE_AA);
      cv::circle(canvas, pixel(v), radius, cv::Scalar(0, 0, 0), 1, cv::LINE_AA);
    }
    const cv::Point e = pixel(node.exemplar);
    const int r = 2 * radius + 2;
    cv::rectangle(canvas, e - cv::Point(r, r), e + cv::Point(r, r),
                  cv::Scalar(0, 0, 0), cv::FILLED);
    cv::putText(canvas, std::to_string(k), e + cv::Point(r + 3, -r),
                cv::FONT_HERSHEY_SIMPLEX, 0.6, cv::Scalar(0, 0, 0), 2,
                cv::LINE_AA);
  }
  for (const int v : tree.unclustered) {
    const cv::Point p = pixel(v);
    cv::drawMarker(canvas, p, cv::Scalar(128, 128, 128),
                   cv::MARKER_TILTED_CROSS, 2 * radius + 2, 2);
  }
  const std::string legend =
      std::to_string(n) + " images, " + std::to_string(tree.kernels.size()) +
      " kernels (black squares: exemplars; outlined: kernel images; "
      "shades: leaf clusters; x: unclustered)";
  cv::putText(canvas, legend, cv::Point(10, 24), cv::FONT_HERSHEY_SIMPLEX, 0.55,
              cv::Scalar(0, 0, 0), 1, cv::LINE_AA);
  return cv::imwrite(png_path, canvas);
}

std::optional<PartitionMap> ReadRunPartitionMap(
    const std::string& database_path, const MatchGraphOptions& match_graph,
    const std::string& output_path, size_t max_images) {
  const std::string tree_path = TmrTreeJsonPath(output_path);
  std::ifstream tree_file(tree_path);
  if (ReadTmrTreeJson(tree_file).image_names.size() > max_images)
    return std::nullopt;
  const MatchGraph graph = ReadMatchGraph(database_path, match_graph);
  std::vector<std::string> names;
  for (const auto& image : graph.images) names.push_back(image.name);
  tree_file.clear();
  tree_file.seekg(0);
  PartitionMap map;
  map.tree = ReadTmrTreeJson(tree_file, names);
  map.similarity = BuildSimilarityGraph(graph);
  map.layout = ForceDirectedLayout(map.similarity);
  return map;
}

bool DrawRunPartitionPicture(const std::string& database_path,
                             const MatchGraphOptions& match_graph,
                             const std::string& output_path) {
  const std::optional<PartitionMap> map =
      ReadRunPartitionMap(database_path, match_graph, output_path);
  if (!map) return false;
  DrawPartitionPicture(
      *map, (std::filesystem::path(output_path) / "partition.png").string());
  return true;
}

}  // namespace tmr
