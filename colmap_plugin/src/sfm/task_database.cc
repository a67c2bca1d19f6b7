// Copyright (c) 2026, the tmr authors. BSD-3-Clause.
#include "sfm/task_database.h"

#include "tmr/io/database_reader.h"

#include <colmap/scene/database.h>
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
