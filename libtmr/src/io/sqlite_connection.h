// Copyright (c) 2026, the tmr authors. BSD-3-Clause.
// Private RAII wrappers around a read-only SQLite connection and statement.
#pragma once

#include <sqlite3.h>

#include <cstdint>
#include <string>

namespace tmr {
namespace internal {

// A strictly read-only connection. Every failure throws DatabaseError with
// the path and SQLite's message.
class ReadOnlySqlite {
 public:
  explicit ReadOnlySqlite(const std::string& path);
  ~ReadOnlySqlite();
  ReadOnlySqlite(const ReadOnlySqlite&) = delete;
  ReadOnlySqlite& operator=(const ReadOnlySqlite&) = delete;

  sqlite3* handle() const { return db_; }
  const std::string& path() const { return path_; }
  [[noreturn]] void Fail(const std::string& problem) const;

  bool HasTable(const std::string& table) const;
  bool HasColumn(const std::string& table, const std::string& column) const;

 private:
  void Open(const std::string& uri);
  std::string path_;
  sqlite3* db_ = nullptr;
};

class Statement {
 public:
  Statement(const ReadOnlySqlite& db, const std::string& sql);
  ~Statement();
  Statement(const Statement&) = delete;
  Statement& operator=(const Statement&) = delete;

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
  const ReadOnlySqlite& db_;
  sqlite3_stmt* stmt_ = nullptr;
};

}  // namespace internal
}  // namespace tmr
