// Copyright (c) 2026, the tmr authors. BSD-3-Clause.
#include "controllers/task_workspace.h"

#include <cstring>
#include <exception>
#include <fstream>
#include <sstream>

#include "io/task_database.h"
#include "tmr/io/atomic_file.h"

namespace tmr {

namespace fs = std::filesystem;

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
     << table.Values(OptionTable::Rows::kTasks) << tree_json;
  return id.str();
}

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

std::string TaskWorkspace::GroupDatabase(int g) const {
  return (folder_ / ("group" + std::to_string(g) + ".db")).string();
}

std::string TaskWorkspace::GroupModels(int g) const {
  return (folder_ / ("group" + std::to_string(g))).string();
}

std::string TaskWorkspace::GroupSeamModels(int g) const {
  return (folder_ / ("group" + std::to_string(g) + "_seams")).string();
}

std::string TaskWorkspace::GroupLightCopy(int g, int linked, int m) const {
  return (fs::path(GroupSeamModels(g)) /
          (linked < 0 ? "all" : "link" + std::to_string(linked)) /
          std::to_string(m))
      .string();
}

std::string TaskWorkspace::JoinDatabase(int job) const {
  return (folder_ / ("join" + std::to_string(job) + ".db")).string();
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
