// Copyright (c) 2026, the tmr authors. BSD-3-Clause.
// Files and SQL for the integration tests: a file's bytes (an input must
// stay byte-identical: ReadFileToString, tmr/io/atomic_file.h) and running
// SQL on a database file (to make other schemas, corrupt rows or a WAL left
// behind).
#pragma once

#include <filesystem>
#include <memory>
#include <string>

#include "tmr/io/atomic_file.h"
#include "tmr/io/database_reader.h"
#include "tmr/io/sqlite.h"

namespace tmr {

// Runs `sql` on a read-write connection to `path` (created when missing)
// and hands the connection back: a WAL database keeps its -wal file until
// the returned connection is destroyed. Throws DatabaseError (the test
// fails with SQLite's message).
inline std::unique_ptr<SqliteDatabase> ExecSql(
    const std::filesystem::path& path, const std::string& sql) {
  auto db = std::make_unique<SqliteDatabase>(path.string(),
                                             SqliteDatabase::Mode::kCreate);
  db->Execute(sql);
  return db;
}

}  // namespace tmr
