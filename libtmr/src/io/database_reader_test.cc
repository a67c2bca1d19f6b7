// Copyright (c) 2026, the tmr authors. BSD-3-Clause.
// Input errors that need no COLMAP. Databases written by COLMAP's own
// Database class are tested in tests/match_graph_colmap_test.cc.
#include "tmr/io/database_reader.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "tmr/io/sqlite.h"

namespace tmr {
namespace {

namespace fs = std::filesystem;

class DatabaseReaderErrors : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ =
        fs::temp_directory_path() /
        ("tmr_reader_" +
         std::string(
             ::testing::UnitTest::GetInstance()->current_test_info()->name()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  // Expects ReadMatchGraph to throw DatabaseError whose message names the
  // path and contains `problem`.
  void ExpectError(const fs::path& path, const std::string& problem) {
    try {
      ReadMatchGraph(path.string());
      FAIL() << "no error for " << path;
    } catch (const DatabaseError& e) {
      const std::string message = e.what();
      EXPECT_NE(message.find(path.string()), std::string::npos) << message;
      EXPECT_NE(message.find(problem), std::string::npos) << message;
      EXPECT_EQ(message.find('\n'), std::string::npos) << message;
    }
  }

  fs::path dir_;
};

TEST_F(DatabaseReaderErrors, MissingFile) {
  ExpectError(dir_ / "missing.db", "no such file");
  EXPECT_FALSE(fs::exists(dir_ / "missing.db"));
}

TEST_F(DatabaseReaderErrors, Directory) { ExpectError(dir_, "is a directory"); }

TEST_F(DatabaseReaderErrors, NotSqlite) {
  const fs::path path = dir_ / "photo.jpg";
  std::ofstream(path) << std::string(4096, 'x');
  ExpectError(path, "not a database");
}

TEST_F(DatabaseReaderErrors, EmptyFileHasNoTables) {
  const fs::path path = dir_ / "empty.db";
  std::ofstream(path).close();
  ExpectError(path, "has no table 'images'");
  EXPECT_EQ(fs::file_size(path), 0u);
}

TEST_F(DatabaseReaderErrors, OtherSqliteDatabase) {
  const fs::path path = dir_ / "other.db";
  SqliteDatabase(path.string(), SqliteDatabase::Mode::kCreate)
      .Execute(
          "CREATE TABLE images(image_id INTEGER, name TEXT);"
          "CREATE TABLE keypoints(image_id INTEGER, rows INT);");
  ExpectError(path, "table 'images' has no column 'camera_id'");
}

TEST(MatchGraphOptions, Check) {
  MatchGraphOptions options;
  EXPECT_TRUE(options.Check());
  options.min_num_matches = 0;
  std::string error;
  EXPECT_FALSE(options.Check(&error));
  EXPECT_NE(error.find("min_num_matches"), std::string::npos);
  options = MatchGraphOptions();
  options.verified_configs = {2, 42};
  EXPECT_FALSE(options.Check());
  options.verified_configs = {};
  EXPECT_FALSE(options.Check());
  EXPECT_THROW(ReadMatchGraph("any.db", options), std::invalid_argument);
}

}  // namespace
}  // namespace tmr
