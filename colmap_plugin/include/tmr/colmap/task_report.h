// Copyright (c) 2026, the tmr authors. BSD-3-Clause.
// The rows of tmr_mapper's report (report.json): each step it ran, and the
// models that stayed apart.
#pragma once

#include <string>
#include <vector>

namespace tmr {

struct TmrTaskReport {
  std::string name;  // "kernel 3", "leaf 3.1", "merge cluster 3", ...
  int num_images = 0;
  int num_registered = 0;
  double seconds = 0.0;
  bool success = false;
  std::string message;
  bool reused = false;  // finished by an earlier, killed run (Tmr.resume)
  // When the step began, in seconds since the run started, and the rows
  // of TmrMapperReport::tasks it waited for (all earlier in the list). A
  // kernel, leaf or cluster-merge task (in_task_graph) ran beside others;
  // the scene assembly's steps run one after the other on one thread.
  double start_s = 0.0;
  std::vector<int> depends = {};
  bool in_task_graph = false;
  // Parts of the step that ran side by side (blocks adjusted at once), in
  // seconds each, and the wall time they took together; the rest of
  // `seconds` ran on one thread.
  std::vector<double> part_seconds = {};
  double parts_wall_s = 0.0;
  // The process's resident memory when the step ended and its peak so far
  // (MiB): a step that raised the peak is the one that needed it.
  double rss_mib = 0.0;
  double peak_mib = 0.0;
  // A link row of the scene assembly (a pair of models aligned, held or
  // refused): its two models as indexes among the models of the "align"
  // row before it (largest first), then their registered images.
  std::vector<int> link = {};
};

// Two final models that verified pairs link but no merge rule joined: what
// a user reads before adding photos between them.
struct TmrWeakLink {
  int model1 = 0;  // output model numbers, model1 < model2
  int model2 = 0;
  int num_pairs = 0;            // verified image pairs between them
  int num_correspondences = 0;  // their verified matches
  // The best try: shared tracks of the best source image, source images
  // registered on the other model's points, and those that fit.
  int num_shared_tracks = 0;
  int num_registered_images = 0;
  int num_supporting_images = 0;
  std::string reason;  // why they stay apart
};

}  // namespace tmr
