// Copyright (c) 2026, the tmr authors. BSD-3-Clause.
#include "drawing/top_view_picture.h"

#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <limits>

namespace tmr {
namespace {

cv::Scalar SetColour(int index) {
  // Well-separated hues, in the order of the sets (largest model first).
  const int hue = (index * 47) % 180;
  cv::Mat hsv(1, 1, CV_8UC3, cv::Scalar(hue, 220, 210)), bgr;
  cv::cvtColor(hsv, bgr, cv::COLOR_HSV2BGR);
  const cv::Vec3b c = bgr.at<cv::Vec3b>(0, 0);
  return cv::Scalar(c[0], c[1], c[2]);
}

}  // namespace

bool DrawTopView(const std::vector<std::array<double, 3>>& reference,
                 const std::vector<CentreSet>& sets,
                 const std::string& png_path, int size_px) {
  if (reference.size() < 2) return false;
  // Principal axes of the reference centres (descending spread).
  cv::Mat points(static_cast<int>(reference.size()), 3, CV_64F);
  for (int i = 0; i < points.rows; ++i)
    for (int j = 0; j < 3; ++j) points.at<double>(i, j) = reference[i][j];
  const cv::PCA pca(points, cv::noArray(), cv::PCA::DATA_AS_ROW);
  auto project = [&](const std::array<double, 3>& c) {
    double x = 0, y = 0;
    for (int j = 0; j < 3; ++j) {
      const double d = c[j] - pca.mean.at<double>(0, j);
      x += d * pca.eigenvectors.at<double>(0, j);
      y += d * pca.eigenvectors.at<double>(1, j);
    }
    return cv::Point2d(x, y);
  };
  double lo_u = std::numeric_limits<double>::max(), hi_u = -lo_u;
  double lo_v = lo_u, hi_v = -lo_u;
  for (const auto& c : reference) {
    const cv::Point2d p = project(c);
    lo_u = std::min(lo_u, p.x);
    hi_u = std::max(hi_u, p.x);
    lo_v = std::min(lo_v, p.y);
    hi_v = std::max(hi_v, p.y);
  }
  const int margin = size_px / 12;
  const int legend = 28 * static_cast<int>(sets.size() + 1);
  const double span = std::max({hi_u - lo_u, hi_v - lo_v, 1e-12});
  const double scale = (size_px - 2 * margin) / span;
  const int height =
      static_cast<int>((hi_v - lo_v) * scale) + 2 * margin + legend;
  cv::Mat image(height, size_px, CV_8UC3, cv::Scalar(255, 255, 255));
  auto pixel = [&](const std::array<double, 3>& c) {
    const cv::Point2d p = project(c);
    return cv::Point(static_cast<int>(margin + (p.x - lo_u) * scale),
                     static_cast<int>(margin + (hi_v - p.y) * scale));
  };
  const int radius = std::max(3, size_px / 150);
  for (const auto& c : reference)
    cv::circle(image, pixel(c), radius + 3, cv::Scalar(170, 170, 170), 2,
               cv::LINE_AA);
  for (size_t s = 0; s < sets.size(); ++s) {
    for (const auto& c : sets[s].centres)
      cv::circle(image, pixel(c), radius, SetColour(static_cast<int>(s)),
                 cv::FILLED, cv::LINE_AA);
  }
  int y = height - legend + 20;
  cv::putText(image, "grey rings: ground truth", cv::Point(margin, y),
              cv::FONT_HERSHEY_SIMPLEX, 0.6, cv::Scalar(120, 120, 120), 1,
              cv::LINE_AA);
  for (size_t s = 0; s < sets.size(); ++s) {
    y += 28;
    cv::circle(image, cv::Point(margin + 6, y - 6), 7,
               SetColour(static_cast<int>(s)), cv::FILLED, cv::LINE_AA);
    cv::putText(image, sets[s].label, cv::Point(margin + 22, y),
                cv::FONT_HERSHEY_SIMPLEX, 0.6, cv::Scalar(40, 40, 40), 1,
                cv::LINE_AA);
  }
  try {
    return cv::imwrite(png_path, image);
  } catch (const cv::Exception&) {
    return false;
  }
}

}  // namespace tmr
