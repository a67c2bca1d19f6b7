// Copyright (c) 2026, the tmr authors. BSD-3-Clause.
#include "controllers/tmr_mapper_report.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <sstream>

#include "controllers/task_graph.h"

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

// The share of the wall time after the last task of the task graph; 0
// without a timeline (SummarizeTimeline).
double AfterTasksShare(const TmrMapperReport& r) {
  return r.total_seconds > 0 && r.tasks_end_s > 0
             ? std::max(0.0, r.total_seconds - r.tasks_end_s) / r.total_seconds
             : 0.0;
}

}  // namespace

std::string ReportJson(const TmrMapperReport& r) {
  std::ostringstream out;
  out << "{\"num_images\": " << r.num_images
      << ", \"partition_s\": " << r.partition_seconds
      << ", \"total_s\": " << r.total_seconds
      << ", \"tasks_end_s\": " << r.tasks_end_s
      << ", \"after_tasks_share\": " << AfterTasksShare(r)
      << ", \"critical_path_s\": " << r.critical_path_s
      << ", \"projected_wall_s\": {";
  for (size_t i = 0; i < r.projected_wall_s.size(); ++i) {
    out << (i ? ", " : "") << "\"" << r.projected_wall_s[i].first
        << "\": " << r.projected_wall_s[i].second;
  }
  out << "}, \"workers\": " << r.num_workers << ", \"critical_path\": [";
  for (size_t i = 0; i < r.critical_path_rows.size(); ++i)
    out << (i ? ", " : "") << r.critical_path_rows[i];
  out << "], \"model_sizes\": [";
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
        << ", \"start_s\": " << t.start_s
        << ", \"in_task_graph\": " << (t.in_task_graph ? "true" : "false")
        << ", \"rss_mib\": " << std::lround(t.rss_mib)
        << ", \"peak_mib\": " << std::lround(t.peak_mib) << ", \"depends\": [";
    for (size_t d = 0; d < t.depends.size(); ++d)
      out << (d ? ", " : "") << t.depends[d];
    out << "]";
    if (!t.part_seconds.empty()) {
      out << ", \"parts_wall_s\": " << t.parts_wall_s
          << ", \"part_seconds\": [";
      for (size_t p = 0; p < t.part_seconds.size(); ++p)
        out << (p ? ", " : "") << t.part_seconds[p];
      out << "]";
    }
    if (!t.link.empty()) {
      out << ", \"link\": [";
      for (size_t k = 0; k < t.link.size(); ++k)
        out << (k ? ", " : "") << t.link[k];
      out << "]";
    }
    out << ", \"message\": \"" << JsonEscaped(t.message) << "\"}";
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

namespace {

// The rows of the longest chain of dependent rows, first to last: each
// row takes its time on one thread and its parts' longest (reused rows 0).
std::vector<int> CriticalPathRows(const std::vector<TmrTaskReport>& rows) {
  const int n = static_cast<int>(rows.size());
  std::vector<double> finish(n, 0.0);
  std::vector<int> previous(n, -1);
  int last = -1;
  for (int t = 0; t < n; ++t) {
    const TmrTaskReport& row = rows[t];
    double own = row.reused ? 0.0 : row.seconds;
    if (!row.reused && !row.part_seconds.empty()) {
      own = std::max(0.0, row.seconds - row.parts_wall_s) +
            *std::max_element(row.part_seconds.begin(), row.part_seconds.end());
    }
    double ready = 0.0;
    for (const int d : row.depends) {
      if (previous[t] < 0 || finish[d] > ready) {
        ready = finish[d];
        previous[t] = d;
      }
    }
    finish[t] = ready + own;
    if (last < 0 || finish[t] >= finish[last]) last = t;
  }
  std::vector<int> path;
  for (int t = last; t >= 0; t = previous[t]) path.push_back(t);
  std::reverse(path.begin(), path.end());
  return path;
}

}  // namespace

void SummarizeTimeline(int num_workers, TmrMapperReport* r) {
  r->num_workers = num_workers;
  r->critical_path_rows = CriticalPathRows(r->tasks);
  const int n = static_cast<int>(r->tasks.size());
  // One node per row for its time on one thread, and one per part that ran
  // side by side, after it; a row that waits for another waits for all of
  // that row's nodes.
  std::vector<double> seconds;
  std::vector<std::vector<int>> depends;
  std::vector<std::vector<int>> row_nodes(n);
  double first_start = std::numeric_limits<double>::max();
  r->tasks_end_s = 0.0;
  for (int t = 0; t < n; ++t) {
    const TmrTaskReport& row = r->tasks[t];
    const double row_seconds = row.reused ? 0.0 : row.seconds;
    const bool parts = !row.reused && !row.part_seconds.empty();
    std::vector<int> waits;
    for (const int d : row.depends)
      waits.insert(waits.end(), row_nodes[d].begin(), row_nodes[d].end());
    const int serial = static_cast<int>(seconds.size());
    seconds.push_back(parts ? std::max(0.0, row_seconds - row.parts_wall_s)
                            : row_seconds);
    depends.push_back(waits);
    row_nodes[t] = {serial};
    if (parts) {
      for (const double part : row.part_seconds) {
        row_nodes[t].push_back(static_cast<int>(seconds.size()));
        seconds.push_back(part);
        depends.push_back({serial});
      }
    }
    if (row.in_task_graph) {
      first_start = std::min(first_start, row.start_s);
      r->tasks_end_s = std::max(r->tasks_end_s, row.start_s + row_seconds);
    }
  }
  const double before = r->tasks_end_s > 0 ? first_start : 0.0;
  const double unaccounted =
      std::max(0.0, r->total_seconds - before -
                        ScheduledWallTime(seconds, depends, num_workers));
  r->critical_path_s =
      before + ScheduledWallTime(seconds, depends, 0) + unaccounted;
  r->projected_wall_s.clear();
  for (const int workers : {2, 4, 8, 16, 64}) {
    r->projected_wall_s.emplace_back(
        workers,
        before + ScheduledWallTime(seconds, depends, workers) + unaccounted);
  }
}

std::string DescribeTimeline(const TmrMapperReport& r) {
  double on16 = 0.0;
  for (const auto& [workers, wall] : r.projected_wall_s)
    if (workers == 16) on16 = wall;
  char line[256];
  std::snprintf(line, sizeof(line),
                "%.1f s after the parallel tasks (%.0f%% of the run); "
                "critical path %.1f s; on 16 workers about %.1f s",
                std::max(0.0, r.total_seconds - r.tasks_end_s),
                100.0 * AfterTasksShare(r), r.critical_path_s, on16);
  return line;
}

}  // namespace tmr
