// Copyright (c) 2026, the tmr authors. BSD-3-Clause.
#include "io/model_files.h"

#include <filesystem>
#include <stdexcept>

namespace tmr {

colmap::Reconstruction ReadModel(const std::string& path) {
  namespace fs = std::filesystem;
  const bool binary = fs::exists(fs::path(path) / "images.bin");
  const bool text = fs::exists(fs::path(path) / "images.txt");
  if (!binary && !text) {
    throw std::runtime_error(
        "'" + path + "' is not a COLMAP model (no images.bin or images.txt)");
  }
  colmap::Reconstruction reconstruction;
  try {
    reconstruction.Read(path);
  } catch (const std::exception& e) {
    throw std::runtime_error("cannot read model '" + path + "': " + e.what());
  }
  return reconstruction;
}

bool WriteModelAtomically(const colmap::Reconstruction& model,
                          const std::string& path) {
  namespace fs = std::filesystem;
  const std::string temporary = path + ".tmp";
  std::error_code ec;
  fs::remove_all(temporary, ec);
  fs::create_directories(temporary, ec);
  if (ec) return false;
  try {
    model.WriteBinary(temporary);
  } catch (const std::exception&) {
    return false;
  }
  fs::remove_all(path, ec);
  fs::rename(temporary, path, ec);
  return !ec;
}

}  // namespace tmr
