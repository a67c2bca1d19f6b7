// Copyright (c) 2026, the tmr authors. BSD-3-Clause.
// libFuzzer target: ReadTmrTreeJson on arbitrary bytes. Every input must end
// in a tree or a std::runtime_error with the problem, never in a crash or a
// sanitizer report; a tree that was read writes back without error.
#include <cstdint>
#include <sstream>
#include <stdexcept>
#include <string>

#include "tmr/partition/tmr_tree.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  std::istringstream in(std::string(reinterpret_cast<const char*>(data), size));
  try {
    const tmr::TmrTree tree = tmr::ReadTmrTreeJson(in);
    std::ostringstream out;
    tmr::WriteTmrTreeJson(tree, out);
  } catch (const std::runtime_error&) {
  }
  return 0;
}
