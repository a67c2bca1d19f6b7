// Copyright (c) 2026, the tmr authors. BSD-3-Clause.
#include "controllers/task_workspace.h"

#include <exception>

#include "controllers/tmr_mapper_support.h"
#include "sfm/task_database.h"
#include "tmr/io/atomic_file.h"

namespace tmr {

namespace fs = std::filesystem;

TaskWorkspace::TaskWorkspace(fs::path folder) : folder_(std::move(folder)) {}

bool TaskWorkspace::Open(const std::string& run_id, bool resume) {
  const fs::path run_id_path = folder_ / "run.id";
  resuming_ = resume && ReadFileToString(run_id_path.string()) == run_id;
  if (resuming_) return true;
  fs::remove_all(folder_);
  fs::create_directories(folder_);
  return WriteFileAtomically(run_id_path.string(), run_id);
}

bool TaskWorkspace::Attach(const std::string& run_id) {
  resuming_ = ReadFileToString((folder_ / "run.id").string()) == run_id;
  return resuming_;
}

bool TaskWorkspace::Finished(const std::string& model,
                             ReconstructionTaskResult* result) const {
  return LoadTaskResult(model + ".result", result) &&
         (!result->success || fs::is_directory(model));
}

std::string TaskWorkspace::KernelModel(int k) const {
  return (folder_ / ("kernel" + std::to_string(k))).string();
}

std::string TaskWorkspace::LeafModel(int k, int l) const {
  return (folder_ / ("leaf" + std::to_string(k) + "_" + std::to_string(l)))
      .string();
}

std::string TaskWorkspace::MergeDatabase() const {
  return (folder_ / "merge.db").string();
}

std::optional<ReconstructionTaskResult> TaskWorkspace::RunOrReuse(
    const std::string& model, const std::string& source_database,
    const std::vector<uint32_t>& images,
    const std::function<ReconstructionTaskResult(const std::string&)>& run,
    bool* reused, std::string* error) const {
  ReconstructionTaskResult result;
  *reused = resuming_ && Finished(model, &result);
  if (*reused) return result;
  const std::string db = model + ".db";
  if (!WriteTaskDatabase(source_database, images, db, error))
    return std::nullopt;
  try {
    result = run(db);
  } catch (const std::exception& e) {  // e.g. COLMAP's database on a full disk
    *error = model + ": " + e.what();
    return std::nullopt;
  }
  if (!SaveTaskResult(result, model + ".result")) {
    *error = "cannot write '" + model + ".result'";
    return std::nullopt;
  }
  return result;
}

}  // namespace tmr
