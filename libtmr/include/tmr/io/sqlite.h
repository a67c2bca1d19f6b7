// Copyright (c) 2026, the tmr authors. BSD-3-Clause.
// The project's one SQLite access layer: every file tmr reads or writes with
// SQLite goes through these two classes (COLMAP's own Database class aside).
// The user's database is only ever opened with Mode::kReadOnly.
#pragma once

#include <cstdint>
#include <string>

struct sqlite3;
struct sqlite3_stmt;

namespace tmr {

// An SQLite "file:" URI that opens `path` read-only and leaves nothing
// beside it. COLMAP keeps databases in WAL journal mode, and a read-only
// connection to a WAL database creates -wal and -shm files it cannot remove;
// so a cleanly closed database (no -wal file) is opened as immutable. One
// with a -wal file is still open in COLMAP or was not closed cleanly and is
// read through the WAL, unless `force_immutable`. The path is
// percent-encoded (quotes too, so the URI can stand in an SQL literal).
std::string ReadOnlySqliteUri(const std::string& path,
                              bool force_immutable = false);

// One connection. Every failure throws DatabaseError (tmr/io/database_reader.h)
// with the path and SQLite's message in one line.
class SqliteDatabase {
 public:
  enum class Mode {
    // Strictly read-only (ReadOnlySqliteUri). A database with a -wal file
    // on a read-only folder is read as immutable when the -wal is empty; a
    // -wal holding changes that cannot be read is an error.
    kReadOnly,
    // An existing file tmr wrote itself (task databases), read-write.
    kReadWrite,
    // Read-write, created when missing (test fixtures).
    kCreate,
  };

  explicit SqliteDatabase(const std::string& path, Mode mode = Mode::kReadOnly,
                          int busy_timeout_ms = 10000);
  ~SqliteDatabase();
  SqliteDatabase(const SqliteDatabase&) = delete;
  SqliteDatabase& operator=(const SqliteDatabase&) = delete;

  sqlite3* handle() const { return db_; }
  const std::string& path() const { return path_; }
  [[noreturn]] void Fail(const std::string& problem) const;

  // Runs one or more statements that return no rows.
  void Execute(const std::string& sql) const;
  bool HasTable(const std::string& table) const;
  bool HasColumn(const std::string& table, const std::string& column) const;

 private:
  void Open(const std::string& uri, int flags);
  void OpenReadOnly();
  std::string path_;
  int busy_timeout_ms_ = 10000;
  sqlite3* db_ = nullptr;
};

class SqliteStatement {
 public:
  SqliteStatement(const SqliteDatabase& db, const std::string& sql);
  ~SqliteStatement();
  SqliteStatement(const SqliteStatement&) = delete;
  SqliteStatement& operator=(const SqliteStatement&) = delete;

  void BindInt(int index, int64_t value);
  void BindText(int index, const std::string& value);
  // Advances to the next row; false when done. Throws on error.
  bool Step();
  int64_t Int(int column) const;
  std::string Text(int column) const;
  const void* Blob(int column) const;
  int BlobBytes(int column) const;
  bool IsNull(int column) const;

 private:
  const SqliteDatabase& db_;
  sqlite3_stmt* stmt_ = nullptr;
};

}  // namespace tmr
