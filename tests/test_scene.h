// Copyright (c) 2026, the tmr authors. BSD-3-Clause.
// A tmr_synth scene for a test suite's fixture.
#pragma once

#include <unistd.h>

#include <filesystem>
#include <string>

#include "tmr/colmap/synthetic_scene.h"

namespace tmr {

// Writes the scene to a fresh folder named after `suite` and this process
// (ctest runs the test cases of a suite as parallel processes: one folder
// each): FOLDER/database.db and the ground truth in FOLDER/gt. Returns the
// folder, or an empty path with the reason in `error`.
inline std::filesystem::path WriteTestScene(
    const std::string& suite, const SyntheticSceneOptions& options,
    std::string* error) {
  namespace fs = std::filesystem;
  const fs::path dir = fs::temp_directory_path() /
                       ("tmr_" + suite + "_" + std::to_string(getpid()));
  fs::remove_all(dir);
  if (!WriteSyntheticScene(options, (dir / "database.db").string(),
                           (dir / "gt").string(), nullptr, error)) {
    return {};
  }
  return dir;
}

}  // namespace tmr
