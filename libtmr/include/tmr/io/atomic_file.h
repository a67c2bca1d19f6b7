// Copyright (c) 2026, the tmr authors. BSD-3-Clause.
#pragma once

#include <string>

namespace tmr {

// Writes a file through a temporary name and a rename, so that an
// interrupted run never leaves a half-written file. False on failure.
bool WriteFileAtomically(const std::string& path, const std::string& content);

// The content of a file; empty when it cannot be read.
std::string ReadFileToString(const std::string& path);

}  // namespace tmr
