// Copyright (c) 2026, the tmr authors. BSD-3-Clause.
// COLMAP model folders read and written whole.
#pragma once

#include <colmap/scene/reconstruction.h>

#include <string>

namespace tmr {

// Reads a COLMAP model folder (binary or text); throws std::runtime_error.
colmap::Reconstruction ReadModel(const std::string& path);

// Writes a model through `path`.tmp and a rename; false on failure.
bool WriteModelAtomically(const colmap::Reconstruction& model,
                          const std::string& path);

}  // namespace tmr
