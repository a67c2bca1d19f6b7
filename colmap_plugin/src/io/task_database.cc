// Copyright (c) 2026, the tmr authors. BSD-3-Clause.
#include "io/task_database.h"

#include <colmap/scene/database.h>
#include <colmap/sensor/models.h>
#include <colmap/util/types.h>

#include <array>
#include <filesystem>
#include <functional>
#include <sstream>

#include "tmr/io/database_reader.h"
#include "tmr/io/sqlite.h"

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
  try {
    colmap::Database::Open(temporary);  // COLMAP's schema, then closed
  } catch (const std::exception& e) {
    *error = "cannot create task database '" + temporary + "': " + e.what();
    return false;
  }

  std::ostringstream ids;
  for (size_t i = 0; i < image_ids.size(); ++i)
    ids << (i ? "," : "") << image_ids[i];
  const std::string set = "(" + ids.str() + ")";
  const std::string pair_base = std::to_string(colmap::kMaxNumImages);
  try {
    // The busy timeout also holds for the attached source: readers of a
    // WAL database whose -shm index is missing (a writer was killed, or
    // COLMAP holds it open) wait for the one that rebuilds it, e.g. two
    // task databases copied at once.
    const SqliteDatabase db(temporary, SqliteDatabase::Mode::kReadWrite);
    db.Execute("ATTACH DATABASE '" + ReadOnlySqliteUri(source_db) +
               "' AS src;");
    // The source's schema version goes with its rows: COLMAP migrates them
    // when it opens the task database (a 3.x database marks relative poses
    // and E, F, H that were not estimated with identity and zeros, 4.x with
    // NULL).
    int64_t source_version = 0;
    {  // finalized before DETACH, which a live statement on src would lock
      SqliteStatement version(db, "PRAGMA src.user_version;");
      if (version.Step()) source_version = version.Int(0);
    }
    db.Execute(
        "BEGIN;"
        "CREATE TEMP TABLE chosen(image_id INTEGER PRIMARY KEY);"
        "INSERT INTO chosen SELECT image_id FROM src.images WHERE image_id "
        "IN " +
        set +
        ";"
        "INSERT INTO cameras(camera_id, model, width, height, params, "
        "prior_focal_length) "
        "  SELECT camera_id, model, width, height, params, "
        "prior_focal_length FROM src.cameras "
        "  WHERE camera_id IN (SELECT camera_id FROM src.images WHERE "
        "image_id IN chosen);"
        "INSERT INTO images(image_id, name, camera_id) "
        "  SELECT image_id, name, camera_id FROM src.images WHERE image_id "
        "IN chosen;"
        "INSERT INTO keypoints(image_id, rows, cols, data) "
        "  SELECT image_id, rows, cols, data FROM src.keypoints WHERE "
        "image_id IN chosen;"
        // A pair's id is image_id1 * kMaxNumImages + image_id2 with
        // image_id1 < image_id2 (COLMAP 3.x and 4.x): each chosen image's
        // pairs as first image are one range of the primary key, so that
        // the copy reads the task's pairs, not the whole table.
        "INSERT INTO two_view_geometries(pair_id, rows, cols, data, config, "
        "F, E, H, qvec, tvec) "
        "  SELECT g.pair_id, g.rows, g.cols, g.data, g.config, g.F, g.E, "
        "g.H, g.qvec, g.tvec "
        "  FROM chosen c JOIN src.two_view_geometries g "
        "  ON g.pair_id >= c.image_id * " +
        pair_base + " AND g.pair_id < (c.image_id + 1) * " + pair_base +
        "  WHERE g.pair_id % " + pair_base +
        " IN chosen;"
        "COMMIT;");
    db.Execute("DETACH DATABASE src; PRAGMA user_version = " +
               std::to_string(source_version) + ";");
  } catch (const DatabaseError& e) {
    *error = std::string("cannot copy images from '") + source_db +
             "' into a task database: " + e.what();
    return false;
  }
  fs::rename(temporary, task_db, ec);
  if (ec) {
    *error = "cannot rename '" + temporary + "': " + ec.message();
    return false;
  }
  return true;
}

bool CheckKeypointsAndCameras(const std::string& source_db,
                              std::string* error) {
  // The first row of `sql` (five integers each) for which `check` names a
  // problem; "" when all is well.
  using Row = std::array<int64_t, 5>;
  const auto first_problem =
      [](const SqliteDatabase& db, const char* sql,
         const std::function<std::string(const Row&)>& check) {
        SqliteStatement stmt(db, sql);
        while (stmt.Step()) {
          Row row;
          for (int i = 0; i < 5; ++i) row[i] = stmt.Int(i);
          std::string problem = check(row);
          if (!problem.empty()) return problem;
        }
        return std::string();
      };
  std::string problem;
  try {
    const SqliteDatabase db(source_db);
    // Keypoint blobs: the query yields only the bad ones.
    problem = first_problem(
        db,
        "SELECT image_id, rows, cols, IFNULL(length(data), 0), 0 FROM "
        "keypoints WHERE rows < 0 OR IFNULL(length(data), 0) != rows * cols "
        "* 4 OR (rows > 0 AND cols NOT IN (2, 4, 6)) LIMIT 1",
        [](const Row& row) {
          return "keypoints of image_id " + std::to_string(row[0]) +
                 ": a blob of " + std::to_string(row[3]) + " bytes for " +
                 std::to_string(row[1]) + " x " + std::to_string(row[2]) +
                 " floats (2, 4 or 6 columns)";
        });
    if (problem.empty()) {
      problem = first_problem(
          db,
          "SELECT camera_id, model, width, height, IFNULL(length(params), 0) "
          "FROM cameras",
          [](const Row& row) -> std::string {
            const std::string camera = "camera_id " + std::to_string(row[0]);
            if (row[1] < 0 || row[1] > 1000 ||
                !colmap::ExistsCameraModelWithId(
                    static_cast<colmap::CameraModelId>(row[1]))) {
              return camera + " has unknown camera model " +
                     std::to_string(row[1]);
            }
            if (row[2] <= 0 || row[3] <= 0) {
              return camera + " has size " + std::to_string(row[2]) + " x " +
                     std::to_string(row[3]);
            }
            const size_t n = colmap::CameraModelNumParams(
                static_cast<colmap::CameraModelId>(row[1]));
            if (static_cast<size_t>(row[4]) != n * sizeof(double)) {
              return camera + " has " + std::to_string(row[4]) +
                     " bytes of parameters, its model needs " +
                     std::to_string(n) + " doubles";
            }
            return "";
          });
    }
  } catch (const DatabaseError& e) {
    *error = e.what();
    return false;
  }
  if (problem.empty()) return true;
  *error = "database '" + source_db + "': " + problem;
  return false;
}

int CountMultiCameraRigs(const std::string& source_db) {
  try {
    const SqliteDatabase db(source_db);
    if (!db.HasTable("rig_sensors")) return 0;
    SqliteStatement stmt(db, "SELECT COUNT(DISTINCT rig_id) FROM rig_sensors");
    return stmt.Step() ? static_cast<int>(stmt.Int(0)) : 0;
  } catch (const DatabaseError&) {
    return 0;
  }
}

std::shared_ptr<colmap::DatabaseCache> LoadTaskDatabaseCache(
    const std::string& source_db, const std::vector<uint32_t>& image_ids,
    const std::string& task_db, int min_num_matches, bool ignore_watermarks,
    std::string* error) {
  if (!WriteTaskDatabase(source_db, image_ids, task_db, error)) return nullptr;
  try {
    colmap::DatabaseCache::Options options;
    options.min_num_matches = min_num_matches;
    options.ignore_watermarks = ignore_watermarks;
    return colmap::DatabaseCache::Create(*colmap::Database::Open(task_db),
                                         options);
  } catch (const std::exception& e) {  // COLMAP's Database on a full disk
    *error = "cannot load task database '" + task_db + "': " + e.what();
    return nullptr;
  }
}

}  // namespace tmr
