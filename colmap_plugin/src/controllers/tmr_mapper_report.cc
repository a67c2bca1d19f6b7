// Copyright (c) 2026, the tmr authors. BSD-3-Clause.
#include "controllers/tmr_mapper_report.h"

#include <sstream>

namespace tmr {
namespace {

std::string JsonEscaped(const std::string& text) {
  std::string escaped;
  for (const char c : text) {
    if (c == '"' || c == '\\') escaped += '\\';
    escaped += c;
  }
  return escaped;
}

}  // namespace

std::string ReportJson(const TmrMapperReport& r) {
  std::ostringstream out;
  out << "{\"num_images\": " << r.num_images
      << ", \"partition_s\": " << r.partition_seconds
      << ", \"total_s\": " << r.total_seconds << ", \"model_sizes\": [";
  for (size_t i = 0; i < r.model_sizes.size(); ++i)
    out << (i ? ", " : "") << r.model_sizes[i];
  out << "], \"tasks\": [";
  for (size_t i = 0; i < r.tasks.size(); ++i) {
    const TmrTaskReport& t = r.tasks[i];
    out << (i ? ",\n  " : "\n  ") << "{\"task\": \"" << t.name
        << "\", \"images\": " << t.num_images
        << ", \"registered\": " << t.num_registered
        << ", \"seconds\": " << t.seconds
        << ", \"success\": " << (t.success ? "true" : "false")
        << ", \"reused\": " << (t.reused ? "true" : "false")
        << ", \"message\": \"" << JsonEscaped(t.message) << "\"}";
  }
  out << "\n], \"weak_links\": [";
  for (size_t i = 0; i < r.weak_links.size(); ++i) {
    const TmrWeakLink& w = r.weak_links[i];
    out << (i ? ",\n  " : "\n  ") << "{\"models\": [" << w.model1 << ", "
        << w.model2 << "], \"verified_pairs\": " << w.num_pairs
        << ", \"correspondences\": " << w.num_correspondences
        << ", \"shared_tracks\": " << w.num_shared_tracks
        << ", \"registered_images\": " << w.num_registered_images
        << ", \"supporting_images\": " << w.num_supporting_images
        << ", \"reason\": \"" << JsonEscaped(w.reason) << "\"}";
  }
  out << "\n]}\n";
  return out.str();
}

}  // namespace tmr
