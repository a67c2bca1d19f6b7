// Copyright (c) 2026, the tmr authors. BSD-3-Clause.
#pragma once

#include <cstdint>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "sfm/reconstruction_task.h"
#include "tmr/colmap/tmr_mapper.h"

namespace tmr {

// A hash of the content of a SQLite database file and of its write-ahead
// log, if any. It leaves out the two header counters SQLite rewrites at every
// commit even when no row changed (COLMAP's own tools, hierarchical_mapper
// among them, open the database for writing and do that), and the
// modification time.
uint64_t DatabaseContentHash(const std::string& path);

// What the kernel and leaf tasks of a run depend on: the partition
// (tree.json), the database's content (DatabaseContentHash) and the options
// that change tasks (OptionRow::changes_tasks). A rerun reuses finished
// tasks only when it matches.
std::string RunFingerprint(const TmrMapperOptions& options,
                           const std::string& tree_json);

// The work folder of a tmr_mapper run (OUT/.tmr_work): one task database
// and one model per kernel and leaf task, and a result record per finished
// task, so that a rerun of a killed run reuses what it finished.
class TaskWorkspace {
 public:
  explicit TaskWorkspace(std::filesystem::path folder);

  // Resumes when `resume` and the folder holds a run with the same
  // `run_id` (RunFingerprint); otherwise empties the folder and records
  // `run_id`. False when the folder cannot be written.
  bool Open(const std::string& run_id, bool resume);
  // For a stage in another process: true when the folder holds a run with
  // `run_id`, whose finished tasks are then reused.
  bool Attach(const std::string& run_id);
  bool resuming() const { return resuming_; }

  const std::filesystem::path& folder() const { return folder_; }
  std::string KernelModel(int k) const;
  std::string LeafModel(int k, int l) const;
  // A task database of all images, for the merges and the completion.
  std::string MergeDatabase() const;
  // A merge stage by parts: group g's task database and its models
  // (folder/0, 1, ... and a record, TmrMapperStages::MergeGroup), the
  // join's light copies of those models (MakeSeamModel, all in
  // GroupSeamModels(g)): model m's on the seam of g's link to group
  // `linked`, or on all of g's seams (linked < 0); and the task database
  // of the seam images of the join's alignment job `job`.
  std::string GroupDatabase(int g) const;
  std::string GroupModels(int g) const;
  std::string GroupSeamModels(int g) const;
  std::string GroupLightCopy(int g, int linked, int m) const;
  std::string JoinDatabase(int job) const;

  // Whether the task whose model is `model` has finished: its record and
  // (when it succeeded) its model are complete; the record in `result`.
  bool Finished(const std::string& model,
                ReconstructionTaskResult* result) const;

  // The result of the task whose model is `model`: an earlier run's when
  // resuming and its record and model are complete (`*reused` set), else
  // `run` on a task database of `images` of `source_database` written
  // beside the model, then recorded. Nothing, with `error`, when the task
  // database or its record cannot be written or `run` throws (COLMAP's
  // database class throws on a full disk).
  std::optional<ReconstructionTaskResult> RunOrReuse(
      const std::string& model, const std::string& source_database,
      const std::vector<uint32_t>& images,
      const std::function<ReconstructionTaskResult(const std::string&)>& run,
      bool* reused, std::string* error) const;

 private:
  std::filesystem::path folder_;
  bool resuming_ = false;
};

}  // namespace tmr
