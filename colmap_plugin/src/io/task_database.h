// Copyright (c) 2026, the tmr authors. BSD-3-Clause.
#pragma once

#include <colmap/scene/database_cache.h>

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace tmr {

// Writes a COLMAP database (schema created by COLMAP's Database class,
// version number of the source, so that COLMAP migrates a 3.x source's rows
// when it opens it) that holds only the given images of `source_db`: their
// cameras, images, keypoints and the two-view geometries among them (rigs
// and frames: none, COLMAP makes trivial ones when it loads). Image
// and camera ids are kept, so models of a task database fit the source. The
// source is attached read-only and never modified; the task database is
// written under a temporary name and renamed when complete. A reconstruction
// task then runs on its own small database: a self-contained unit of work
// with its input on disk. Returns false with a reason in `error`.
bool WriteTaskDatabase(const std::string& source_db,
                       const std::vector<uint32_t>& image_ids,
                       const std::string& task_db, std::string* error);

// Checks what COLMAP's Database class reads but tmr's own reader does not:
// every keypoint blob holds rows x cols floats with 2, 4 or 6 columns, and
// every camera has a known model, a positive size and as many parameters
// as its model needs. COLMAP stops on a failed check instead. False with
// the first problem in `error`.
bool CheckKeypointsAndCameras(const std::string& source_db, std::string* error);

// The rigs of `source_db` that hold more than one camera (rigs with rows in
// COLMAP 4's rig_sensors table, which lists the sensors besides the
// reference one); 0 for a database without rigs (COLMAP 3.x) or that
// cannot be read. Task databases hold no rigs: tmr maps the images of such
// rigs as independent cameras.
int CountMultiCameraRigs(const std::string& source_db);

// COLMAP's in-memory correspondences of the given images, loaded from a
// task database written to `task_db` (COLMAP's Database class writes to the
// file it opens, so it never opens the input). Null with a reason in
// `error`.
std::shared_ptr<colmap::DatabaseCache> LoadTaskDatabaseCache(
    const std::string& source_db, const std::vector<uint32_t>& image_ids,
    const std::string& task_db, int min_num_matches, bool ignore_watermarks,
    std::string* error);

}  // namespace tmr
