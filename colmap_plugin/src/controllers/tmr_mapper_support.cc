// Copyright (c) 2026, the tmr authors. BSD-3-Clause.
#include "controllers/tmr_mapper_support.h"

#include <glog/logging.h>
#if defined(__GLIBC__)
#include <malloc.h>
#endif

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>
#include <thread>
#include <vector>

namespace tmr {

colmap::IncrementalPipelineOptions ColmapOptions(
    const TmrMapperOptions& options, int num_threads) {
  const MapperPassThroughOptions& m = options.mapper;
  colmap::IncrementalPipelineOptions o;
  o.min_num_matches = m.min_num_matches;
  o.ignore_watermarks = m.ignore_watermarks;
  o.min_model_size = m.min_model_size;
  o.mapper.init_min_num_inliers = m.init_min_num_inliers;
  o.mapper.abs_pose_min_num_inliers = m.abs_pose_min_num_inliers;
  o.mapper.init_max_forward_motion = m.init_max_forward_motion;
  o.mapper.init_min_tri_angle = m.init_min_tri_angle;
  o.mapper.filter_min_tri_angle = m.filter_min_tri_angle;
  o.mapper.filter_max_reproj_error = m.filter_max_reproj_error;
  o.triangulation.min_angle = m.tri_min_angle;
  o.ba_refine_focal_length = m.ba_refine_focal_length;
  o.ba_refine_principal_point = m.ba_refine_principal_point;
  o.ba_refine_extra_params = m.ba_refine_extra_params;
  o.ba_global_max_num_iterations = m.ba_global_max_num_iterations;
  o.ba_global_max_refinements = m.ba_global_max_refinements;
  o.ba_global_function_tolerance = m.ba_global_function_tolerance;
  o.mapper.ba_local_num_images = m.ba_local_num_images;
  o.ba_local_max_num_iterations = m.ba_local_max_num_iterations;
  o.ba_local_max_refinements = m.ba_local_max_refinements;
  o.ba_local_function_tolerance = m.ba_local_function_tolerance;
  o.num_threads = options.task.repeatable ? 1 : num_threads;
  o.random_seed =
      static_cast<int>(options.tree.seed % std::numeric_limits<int>::max());
  return o;
}

uint64_t DatabaseContentHash(const std::string& path) {
  // Header bytes SQLite rewrites at every commit, even of no change: the
  // file change counter and the version-valid-for number.
  const auto is_counter = [](uint64_t at) {
    return (at >= 24 && at < 28) || (at >= 92 && at < 96);
  };
  uint64_t hash = 0x9E3779B97F4A7C15ull;
  const auto mix = [&hash](uint64_t word) {
    hash ^= word;
    hash *= 0xBF58476D1CE4E5B9ull;
    hash ^= hash >> 31;
  };
  for (const std::string& file : {path, path + "-wal"}) {
    std::ifstream in(file, std::ios::binary);
    std::vector<char> buffer(1 << 20);
    uint64_t offset = 0;
    while (in) {
      in.read(buffer.data(), static_cast<std::streamsize>(buffer.size()));
      const size_t n = static_cast<size_t>(in.gcount());
      if (file == path) {
        for (size_t i = 0; i < n && offset + i < 96; ++i)
          if (is_counter(offset + i)) buffer[i] = 0;
      }
      size_t i = 0;
      for (uint64_t word; i + 8 <= n; i += 8) {
        std::memcpy(&word, buffer.data() + i, 8);
        mix(word);
      }
      for (; i < n; ++i) mix(static_cast<unsigned char>(buffer[i]));
      offset += n;
    }
    mix(offset);
  }
  return hash;
}

std::string RunFingerprint(const TmrMapperOptions& options,
                           const std::string& tree_json) {
  TmrMapperOptions copy = options;
  OptionTable table;
  copy.AddTo(&table);
  std::ostringstream id;
  id << "database " << std::hex << DatabaseContentHash(options.database_path)
     << "\n"
     << table.Values(/*tasks_only=*/true) << tree_json;
  return id.str();
}

std::string ReadFileToString(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream content;
  content << in.rdbuf();
  return in ? content.str() : std::string();
}

MergedModelAdjustment MergedAdjustment(const TmrMapperOptions& options,
                                       bool while_merging) {
  MergedModelAdjustment adjustment;
  adjustment.enabled = options.refinement.enabled;
  adjustment.max_block_images = options.refinement.max_block_images;
  if (while_merging)
    adjustment.longest_tracks_per_image = options.refinement.points_per_image;
  else
    adjustment.max_refinements = options.mapper.ba_global_max_refinements;
  return adjustment;
}

void ReleaseFreedMemory() {
#if defined(__GLIBC__)
  malloc_trim(0);
#endif
}

double SecondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start)
      .count();
}

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

void ConfigureColmapLogging(const char* program, bool verbose) {
  FLAGS_logtostderr = true;
  FLAGS_minloglevel = verbose ? google::GLOG_INFO : google::GLOG_WARNING;
  if (!google::IsGoogleLoggingInitialized()) google::InitGoogleLogging(program);
}

}  // namespace tmr
