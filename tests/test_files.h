// Copyright (c) 2026, the tmr authors. BSD-3-Clause.
// Files and SQL for the integration tests: reading a file's bytes (an input
// must stay byte-identical) and running SQL on a database file (to make
// other schemas, corrupt rows or a WAL left behind).
#pragma once

#include <gtest/gtest.h>
#include <sqlite3.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace tmr {

// The bytes of a file ("" when it cannot be read).
inline std::string ReadFileBytes(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream out;
  out << in.rdbuf();
  return out.str();
}

// Runs `sql` on a read-write connection to `path`. With `keep_open` the
// connection is handed back open (so that a WAL database keeps its -wal
// file until the caller closes it).
inline void ExecSql(const std::filesystem::path& path, const std::string& sql,
                    sqlite3** keep_open = nullptr) {
  sqlite3* db = nullptr;
  ASSERT_EQ(sqlite3_open(path.c_str(), &db), SQLITE_OK);
  char* error = nullptr;
  const int rc = sqlite3_exec(db, sql.c_str(), nullptr, nullptr, &error);
  const std::string message = error ? error : "";
  sqlite3_free(error);
  if (keep_open) {
    *keep_open = db;
  } else {
    sqlite3_close(db);
  }
  ASSERT_EQ(rc, SQLITE_OK) << message;
}

}  // namespace tmr
