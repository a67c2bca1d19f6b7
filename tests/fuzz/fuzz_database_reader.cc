// Copyright (c) 2026, the tmr authors. BSD-3-Clause.
// libFuzzer target: ReadMatchGraph on arbitrary bytes as a database file.
// Every input must end in a match graph or a DatabaseError, never in a
// crash, a sanitizer report, a hang or an allocation beyond the file's size.
#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <string>

#include "tmr/io/database_reader.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  static const std::string path =
      "/tmp/tmr_fuzz_database_" + std::to_string(getpid()) + ".db";
  if (FILE* file = std::fopen(path.c_str(), "wb")) {
    std::fwrite(data, 1, size, file);
    std::fclose(file);
  } else {
    return 0;
  }
  try {
    const tmr::MatchGraph graph = tmr::ReadMatchGraph(path);
    (void)graph;
  } catch (const tmr::DatabaseError&) {
  }
  return 0;
}
