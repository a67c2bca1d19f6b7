// Copyright (c) 2026, the tmr authors. BSD-3-Clause.
#include "sfm/task_database.h"

#include "tmr/io/database_reader.h"

#include <colmap/scene/database.h>
#include <colmap/sensor/models.h>
#include <sqlite3.h>

#include <filesystem>
#include <sstream>

namespace tmr {
bool WriteTaskDatabase(const std::string& source_db,
                       const std::vector<uint32_t>& image_ids,
                       const std::string& task_db, std::string* error) {
  namespace fs = std::filesystem;
  const std::string temporary = task_db + ".tmp";
  std::error_code ec;
  fs::remove(temporary, ec);
  fs::remove(temporary + "-wal", ec);
  fs::remove(temporary + "-shm", ec);
  { colmap::Database create_schema(temporary); }

  sqlite3* db = nullptr;
  if (sqlite3_open_v2(temporary.c_str(), &db,
                      SQLITE_OPEN_READWRITE | SQLITE_OPEN_URI,
                      nullptr) != SQLITE_OK) {
    *error = "cannot open task database '" + temporary + "'";
    sqlite3_close(db);
    return false;
  }
  std::ostringstream ids;
  for (size_t i = 0; i < image_ids.size(); ++i)
    ids << (i ? "," : "") << image_ids[i];
  const std::string set = "(" + ids.str() + ")";
  const std::string sql =
      "ATTACH DATABASE '" + ReadOnlySqliteUri(source_db) +
      "' AS src;"
      "BEGIN;"
      "CREATE TEMP TABLE chosen(image_id INTEGER PRIMARY KEY);"
      "INSERT INTO chosen SELECT image_id FROM src.images WHERE image_id IN " +
      set +
      ";"
      "INSERT INTO cameras(camera_id, model, width, height, params, "
      "prior_focal_length) "
      "  SELECT camera_id, model, width, height, params, prior_focal_length "
      "FROM src.cameras "
      "  WHERE camera_id IN (SELECT camera_id FROM src.images WHERE image_id "
      "IN chosen);"
      "INSERT INTO images(image_id, name, camera_id) "
      "  SELECT image_id, name, camera_id FROM src.images WHERE image_id IN "
      "chosen;"
      "INSERT INTO keypoints(image_id, rows, cols, data) "
      "  SELECT image_id, rows, cols, data FROM src.keypoints WHERE image_id "
      "IN chosen;"
      "INSERT INTO two_view_geometries(pair_id, rows, cols, data, config, F, "
      "E, H, qvec, tvec) "
      "  SELECT pair_id, rows, cols, data, config, F, E, H, qvec, tvec "
      "  FROM src.two_view_geometries "
      "  WHERE pair_id % 2147483647 IN chosen AND pair_id / 2147483647 IN "
      "chosen;"
      "COMMIT;"
      "DETACH DATABASE src;";
  char* message = nullptr;
  const int rc = sqlite3_exec(db, sql.c_str(), nullptr, nullptr, &message);
  if (rc != SQLITE_OK) {
    *error = "cannot copy images into task database '" + task_db +
             "': " + (message ? message : "unknown SQLite error");
    sqlite3_free(message);
    sqlite3_close(db);
    return false;
  }
  sqlite3_close(db);
  fs::rename(temporary, task_db, ec);
  if (ec) {
    *error = "cannot rename '" + temporary + "': " + ec.message();
    return false;
  }
  return true;
}

bool CheckKeypointsAndCameras(const std::string& source_db,
                              std::string* error) {
  sqlite3* db = nullptr;
  const auto fail = [&](const std::string& problem) {
    *error = "database '" + source_db + "': " + problem;
    sqlite3_close(db);
    return false;
  };
  if (sqlite3_open_v2(ReadOnlySqliteUri(source_db).c_str(), &db,
                      SQLITE_OPEN_READONLY | SQLITE_OPEN_URI,
                      nullptr) != SQLITE_OK) {
    return fail("cannot open");
  }
  sqlite3_busy_timeout(db, 10000);
  // Each query yields the first bad row, if any: id, four numbers.
  const auto first_bad_row = [&](const char* sql, int64_t(&row)[5],
                                 bool* found) {
    sqlite3_stmt* stmt = nullptr;
    if (sqlite3_prepare_v2(db, sql, -1, &stmt, nullptr) != SQLITE_OK)
      return false;
    const int rc = sqlite3_step(stmt);
    *found = rc == SQLITE_ROW;
    for (int i = 0; *found && i < 5; ++i)
      row[i] = sqlite3_column_int64(stmt, i);
    sqlite3_finalize(stmt);
    return rc == SQLITE_ROW || rc == SQLITE_DONE;
  };
  int64_t row[5] = {};
  bool found = false;
  if (!first_bad_row("SELECT image_id, rows, cols, IFNULL(length(data), 0), 0 "
                     "FROM keypoints WHERE rows < 0 OR IFNULL(length(data), 0)"
                     " != rows * cols * 4 OR (rows > 0 AND cols NOT IN "
                     "(2, 4, 6)) LIMIT 1",
                     row, &found)) {
    return fail(std::string("cannot read keypoints: ") + sqlite3_errmsg(db));
  }
  if (found) {
    return fail("keypoints of image_id " + std::to_string(row[0]) +
                ": a blob of " + std::to_string(row[3]) + " bytes for " +
                std::to_string(row[1]) + " x " + std::to_string(row[2]) +
                " floats (2, 4 or 6 columns)");
  }
  sqlite3_stmt* stmt = nullptr;
  if (sqlite3_prepare_v2(db,
                         "SELECT camera_id, model, width, height, "
                         "IFNULL(length(params), 0) FROM cameras",
                         -1, &stmt, nullptr) != SQLITE_OK) {
    return fail(std::string("cannot read cameras: ") + sqlite3_errmsg(db));
  }
  std::string problem;
  while (problem.empty() && sqlite3_step(stmt) == SQLITE_ROW) {
    for (int i = 0; i < 5; ++i) row[i] = sqlite3_column_int64(stmt, i);
    const std::string camera = "camera_id " + std::to_string(row[0]);
    if (row[1] < 0 || row[1] > 1000 ||
        !colmap::ExistsCameraModelWithId(
            static_cast<colmap::CameraModelId>(row[1]))) {
      problem = camera + " has unknown camera model " + std::to_string(row[1]);
    } else if (row[2] <= 0 || row[3] <= 0) {
      problem = camera + " has size " + std::to_string(row[2]) + " x " +
                std::to_string(row[3]);
    } else if (const size_t n = colmap::CameraModelNumParams(
                   static_cast<colmap::CameraModelId>(row[1]));
               static_cast<size_t>(row[4]) != n * sizeof(double)) {
      problem = camera + " has " + std::to_string(row[4]) +
                " bytes of parameters, its model needs " + std::to_string(n) +
                " doubles";
    }
  }
  sqlite3_finalize(stmt);
  if (!problem.empty()) return fail(problem);
  sqlite3_close(db);
  return true;
}

std::shared_ptr<colmap::DatabaseCache> LoadTaskDatabaseCache(
    const std::string& source_db, const std::vector<uint32_t>& image_ids,
    const std::string& task_db, int min_num_matches, bool ignore_watermarks,
    std::string* error) {
  if (!WriteTaskDatabase(source_db, image_ids, task_db, error)) return nullptr;
  colmap::Database database(task_db);
  return colmap::DatabaseCache::Create(database, min_num_matches,
                                       ignore_watermarks, {});
}

}  // namespace tmr
