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
  o.num_threads = options.repeatable ? 1 : num_threads;
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

std::string RunFingerprint(const TmrMapperOptions& o,
                           const std::string& tree_json) {
  const MapperPassThroughOptions& m = o.mapper;
  std::ostringstream id;
  id.precision(17);
  id << "database " << std::hex << DatabaseContentHash(o.database_path)
     << std::dec << "\nmapper " << m.min_num_matches << " "
     << m.ignore_watermarks << " " << m.init_min_num_inliers << " "
     << m.min_model_size << " " << m.abs_pose_min_num_inliers << " "
     << m.filter_max_reproj_error << " " << m.tri_min_angle << " "
     << m.ba_refine_focal_length << " " << m.ba_refine_principal_point << " "
     << m.ba_refine_extra_params << " " << m.ba_global_max_num_iterations << " "
     << m.init_max_forward_motion << " " << m.init_min_tri_angle << " "
     << m.filter_min_tri_angle << " " << m.ba_global_max_refinements << " "
     << m.ba_global_function_tolerance << " " << m.ba_local_num_images << " "
     << m.ba_local_max_num_iterations << " " << m.ba_local_max_refinements
     << " " << m.ba_local_function_tolerance << "\ntasks "
     << o.fix_base_in_leaves << " " << o.task_ba_global_ratio << " "
     << o.check_kernels << " " << o.repeatable << "\n"
     << tree_json;
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
  adjustment.enabled = options.refine_merged_models;
  adjustment.max_block_images = options.ba_max_block_images;
  if (while_merging)
    adjustment.longest_tracks_per_image = options.merge_refine_points_per_image;
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

bool TmrMapperOptions::Check(std::string* error) const {
  auto fail = [&](const std::string& message) {
    if (error) *error = message;
    return false;
  };
  if (database_path.empty()) return fail("database_path is empty");
  if (output_path.empty()) return fail("output_path is empty");
  if (num_threads == 0 || num_threads < -1)
    return fail("num_threads must be -1 or >= 1");
  if (merge_min_shared_tracks < 3)
    return fail("merge_min_shared_tracks must be >= 3");
  if (merge_register_images < 0)
    return fail("Tmr.merge_register_images must be >= 0");
  if (!(task_ba_global_ratio > 1.0 && std::isfinite(task_ba_global_ratio)))
    return fail("Tmr.task_ba_global_ratio must be > 1");
  if (!(merge_refine_growth >= 1.0 && std::isfinite(merge_refine_growth)))
    return fail("Tmr.merge_refine_growth must be >= 1");
  if (ba_max_block_images < 0)
    return fail("Tmr.ba_max_block_images must be >= 0");
  if (merge_refine_points_per_image < 0)
    return fail("Tmr.merge_refine_points_per_image must be >= 0");
  if (mapper.min_num_matches < 1)
    return fail("Mapper.min_num_matches must be >= 1");
  if (mapper.min_model_size < 1)
    return fail("Mapper.min_model_size must be >= 1");
  if (!(mapper.init_max_forward_motion >= 0 &&
        mapper.init_max_forward_motion <= 1))
    return fail("Mapper.init_max_forward_motion must be in [0, 1]");
  if (!(mapper.init_min_tri_angle >= 0 && mapper.init_min_tri_angle < 180) ||
      !(mapper.filter_min_tri_angle >= 0 && mapper.filter_min_tri_angle < 180))
    return fail("Mapper.*_tri_angle must be in [0, 180)");
  if (mapper.init_min_num_inliers < 1 || mapper.abs_pose_min_num_inliers < 1 ||
      mapper.ba_global_max_num_iterations < 1)
    return fail("Mapper.*_min_num_inliers and iterations must be >= 1");
  if (mapper.ba_global_max_refinements < 1 || mapper.ba_local_num_images < 2 ||
      mapper.ba_local_max_num_iterations < 1 ||
      mapper.ba_local_max_refinements < 1)
    return fail(
        "Mapper.ba_*_max_refinements and iterations must be >= 1, "
        "ba_local_num_images >= 2");
  if (!(mapper.ba_global_function_tolerance >= 0) ||
      !(mapper.ba_local_function_tolerance >= 0))
    return fail("Mapper.ba_*_function_tolerance must be >= 0");
  if (!(mapper.filter_max_reproj_error > 0) || !(mapper.tri_min_angle > 0))
    return fail("Mapper.filter_max_reproj_error and tri_min_angle must be > 0");
  return match_graph.Check(error) && tree.Check(error);
}

void ConfigureColmapLogging(const char* program, bool verbose) {
  FLAGS_logtostderr = true;
  FLAGS_minloglevel = verbose ? google::GLOG_INFO : google::GLOG_WARNING;
  if (!google::IsGoogleLoggingInitialized()) google::InitGoogleLogging(program);
}

}  // namespace tmr
