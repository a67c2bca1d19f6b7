// Copyright (c) 2026, the tmr authors. BSD-3-Clause.
#include "io/sqlite_connection.h"

#include <filesystem>
#include <string_view>

#include "tmr/io/database_reader.h"

namespace tmr {
namespace internal {
namespace {

// Percent-encodes a file path for an SQLite "file:" URI.
std::string PathToUri(const std::string& path, bool immutable) {
  std::string uri = "file:";
  for (const char c : path) {
    if (c == '%' || c == '?' || c == '#' ||
        static_cast<unsigned char>(c) < 32) {
      static const char kHex[] = "0123456789ABCDEF";
      uri += '%';
      uri += kHex[(static_cast<unsigned char>(c) >> 4) & 0xF];
      uri += kHex[static_cast<unsigned char>(c) & 0xF];
    } else {
      uri += c;
    }
  }
  uri += immutable ? "?mode=ro&immutable=1" : "?mode=ro";
  return uri;
}

}  // namespace

ReadOnlySqlite::ReadOnlySqlite(const std::string& path) : path_(path) {
  std::error_code ec;
  const auto status = std::filesystem::status(path, ec);
  if (!std::filesystem::exists(status)) Fail("no such file");
  if (std::filesystem::is_directory(status)) Fail("is a directory, not a file");
  // COLMAP keeps its databases in WAL journal mode. A read-only connection
  // to a WAL database creates -wal and -shm files beside it that it cannot
  // remove, so a cleanly closed database (no -wal file) is opened as an
  // immutable file, which touches nothing. A database with a -wal file is
  // still open in COLMAP or was not closed cleanly: read it through the WAL,
  // and as immutable if that is impossible (read-only folder).
  const bool has_wal = std::filesystem::exists(path + "-wal", ec);
  Open(/*immutable=*/!has_wal);
  if (!has_wal) return;
  try {
    HasTable("images");
  } catch (const DatabaseError&) {
    const int code = sqlite3_errcode(db_);
    if (code != SQLITE_CANTOPEN && code != SQLITE_READONLY) throw;
    sqlite3_close(db_);
    db_ = nullptr;
    Open(/*immutable=*/true);
  }
}

ReadOnlySqlite::~ReadOnlySqlite() { sqlite3_close(db_); }

void ReadOnlySqlite::Open(bool immutable) {
  const int rc =
      sqlite3_open_v2(PathToUri(path_, immutable).c_str(), &db_,
                      SQLITE_OPEN_READONLY | SQLITE_OPEN_URI, nullptr);
  if (rc != SQLITE_OK) {
    const std::string message = db_ ? sqlite3_errmsg(db_) : sqlite3_errstr(rc);
    sqlite3_close(db_);
    db_ = nullptr;
    Fail("cannot open: " + message);
  }
  sqlite3_busy_timeout(db_, 10000);
}

void ReadOnlySqlite::Fail(const std::string& problem) const {
  throw DatabaseError("database '" + path_ + "': " + problem);
}

bool ReadOnlySqlite::HasTable(const std::string& table) const {
  Statement stmt(*this,
                 "SELECT 1 FROM sqlite_master WHERE type='table' AND name=?");
  stmt.BindText(1, table);
  return stmt.Step();
}

bool ReadOnlySqlite::HasColumn(const std::string& table,
                               const std::string& column) const {
  Statement stmt(*this, "SELECT 1 FROM pragma_table_info(?) WHERE name=?");
  stmt.BindText(1, table);
  stmt.BindText(2, column);
  return stmt.Step();
}

Statement::Statement(const ReadOnlySqlite& db, const std::string& sql)
    : db_(db) {
  if (sqlite3_prepare_v2(db.handle(), sql.c_str(), -1, &stmt_, nullptr) !=
      SQLITE_OK) {
    db.Fail(sqlite3_errmsg(db.handle()));
  }
}

Statement::~Statement() { sqlite3_finalize(stmt_); }

void Statement::BindInt(int index, int64_t value) {
  sqlite3_bind_int64(stmt_, index, value);
}

void Statement::BindText(int index, const std::string& value) {
  sqlite3_bind_text(stmt_, index, value.c_str(), -1, SQLITE_TRANSIENT);
}

bool Statement::Step() {
  const int rc = sqlite3_step(stmt_);
  if (rc == SQLITE_ROW) return true;
  if (rc == SQLITE_DONE) return false;
  db_.Fail(sqlite3_errmsg(db_.handle()));
}

int64_t Statement::Int(int column) const {
  return sqlite3_column_int64(stmt_, column);
}

std::string Statement::Text(int column) const {
  const auto* text = sqlite3_column_text(stmt_, column);
  return text ? reinterpret_cast<const char*>(text) : "";
}

const void* Statement::Blob(int column) const {
  return sqlite3_column_blob(stmt_, column);
}

int Statement::BlobBytes(int column) const {
  return sqlite3_column_bytes(stmt_, column);
}

bool Statement::IsNull(int column) const {
  return sqlite3_column_type(stmt_, column) == SQLITE_NULL;
}

}  // namespace internal
}  // namespace tmr
