// Copyright (c) 2026, the tmr authors. BSD-3-Clause.
#include "tmr/io/sqlite.h"

#include <sqlite3.h>

#include <filesystem>

#include "tmr/io/database_reader.h"

namespace tmr {

SqliteDatabase::SqliteDatabase(const std::string& path, Mode mode,
                               int busy_timeout_ms)
    : path_(path), busy_timeout_ms_(busy_timeout_ms) {
  if (mode == Mode::kReadOnly) {
    OpenReadOnly();
    return;
  }
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec))
    Fail("is a directory, not a file");
  if (mode == Mode::kReadWrite && !std::filesystem::exists(path, ec))
    Fail("no such file");
  Open(path, SQLITE_OPEN_READWRITE |
                 (mode == Mode::kCreate ? SQLITE_OPEN_CREATE : 0));
}

void SqliteDatabase::OpenReadOnly() {
  constexpr int kFlags = SQLITE_OPEN_READONLY | SQLITE_OPEN_URI;
  std::error_code ec;
  const auto status = std::filesystem::status(path_, ec);
  if (!std::filesystem::exists(status)) Fail("no such file");
  if (std::filesystem::is_directory(status)) Fail("is a directory, not a file");
  Open(ReadOnlySqliteUri(path_), kFlags);
  // A throwing constructor runs no destructor: close the handle here.
  try {
    // A database with a -wal file on a read-only folder cannot be read
    // through the WAL; it can as an immutable file when the -wal is empty.
    // A -wal that holds changes and cannot be read is an error: the
    // database file alone would be read without them.
    try {
      HasTable("images");
    } catch (const DatabaseError&) {
      const int code = sqlite3_errcode(db_);
      if (code != SQLITE_CANTOPEN && code != SQLITE_READONLY) throw;
      const std::filesystem::path wal = path_ + "-wal";
      std::error_code wal_ec;
      if (std::filesystem::exists(wal, wal_ec) &&
          (!std::filesystem::is_regular_file(wal, wal_ec) ||
           std::filesystem::file_size(wal, wal_ec) != 0)) {
        Fail("its write-ahead log '" + wal.string() +
             "' holds changes that cannot be read (" + sqlite3_errmsg(db_) +
             "): copy the database with its -wal file to a writable folder");
      }
      sqlite3_close(db_);
      db_ = nullptr;
      Open(ReadOnlySqliteUri(path_, /*force_immutable=*/true), kFlags);
    }
  } catch (...) {
    sqlite3_close(db_);
    db_ = nullptr;
    throw;
  }
}

SqliteDatabase::~SqliteDatabase() { sqlite3_close(db_); }

void SqliteDatabase::Open(const std::string& uri, int flags) {
  const int rc = sqlite3_open_v2(uri.c_str(), &db_, flags, nullptr);
  if (rc != SQLITE_OK) {
    const std::string message = db_ ? sqlite3_errmsg(db_) : sqlite3_errstr(rc);
    sqlite3_close(db_);
    db_ = nullptr;
    Fail("cannot open: " + message);
  }
  sqlite3_busy_timeout(db_, busy_timeout_ms_);
}

void SqliteDatabase::Execute(const std::string& sql) const {
  char* message = nullptr;
  if (sqlite3_exec(db_, sql.c_str(), nullptr, nullptr, &message) != SQLITE_OK) {
    const std::string problem = message ? message : sqlite3_errmsg(db_);
    sqlite3_free(message);
    Fail(problem);
  }
}

void SqliteDatabase::Fail(const std::string& problem) const {
  throw DatabaseError("database '" + path_ + "': " + problem);
}

bool SqliteDatabase::HasTable(const std::string& table) const {
  SqliteStatement stmt(
      *this, "SELECT 1 FROM sqlite_master WHERE type='table' AND name=?");
  stmt.BindText(1, table);
  return stmt.Step();
}

bool SqliteDatabase::HasColumn(const std::string& table,
                               const std::string& column) const {
  SqliteStatement stmt(*this,
                       "SELECT 1 FROM pragma_table_info(?) WHERE name=?");
  stmt.BindText(1, table);
  stmt.BindText(2, column);
  return stmt.Step();
}

SqliteStatement::SqliteStatement(const SqliteDatabase& db,
                                 const std::string& sql)
    : db_(db) {
  if (sqlite3_prepare_v2(db.handle(), sql.c_str(), -1, &stmt_, nullptr) !=
      SQLITE_OK) {
    db.Fail(sqlite3_errmsg(db.handle()));
  }
}

SqliteStatement::~SqliteStatement() { sqlite3_finalize(stmt_); }

void SqliteStatement::BindInt(int index, int64_t value) {
  sqlite3_bind_int64(stmt_, index, value);
}

void SqliteStatement::BindText(int index, const std::string& value) {
  sqlite3_bind_text(stmt_, index, value.c_str(), -1, SQLITE_TRANSIENT);
}

bool SqliteStatement::Step() {
  const int rc = sqlite3_step(stmt_);
  if (rc == SQLITE_ROW) return true;
  if (rc == SQLITE_DONE) return false;
  db_.Fail(sqlite3_errmsg(db_.handle()));
}

int64_t SqliteStatement::Int(int column) const {
  return sqlite3_column_int64(stmt_, column);
}

std::string SqliteStatement::Text(int column) const {
  const auto* text = sqlite3_column_text(stmt_, column);
  return text ? reinterpret_cast<const char*>(text) : "";
}

const void* SqliteStatement::Blob(int column) const {
  return sqlite3_column_blob(stmt_, column);
}

int SqliteStatement::BlobBytes(int column) const {
  return sqlite3_column_bytes(stmt_, column);
}

bool SqliteStatement::IsNull(int column) const {
  return sqlite3_column_type(stmt_, column) == SQLITE_NULL;
}

std::string ReadOnlySqliteUri(const std::string& path, bool force_immutable) {
  std::string uri = "file:";
  for (const char c : path) {
    const auto byte = static_cast<unsigned char>(c);
    if (c == '%' || c == '?' || c == '#' || c == '\'' || byte < 32) {
      static const char kHex[] = "0123456789ABCDEF";
      uri += '%';
      uri += kHex[byte >> 4];
      uri += kHex[byte & 0xF];
    } else {
      uri += c;
    }
  }
  std::error_code ec;
  const bool through_wal =
      !force_immutable && std::filesystem::exists(path + "-wal", ec);
  return uri + (through_wal ? "?mode=ro" : "?mode=ro&immutable=1");
}

}  // namespace tmr
