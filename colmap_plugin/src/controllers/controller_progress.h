// Copyright (c) 2026, the tmr authors. BSD-3-Clause.
// Progress of COLMAP's extraction and matching threads, read from the
// database they write.
#pragma once

#include <colmap/util/threading.h>

#include <cstdint>
#include <functional>
#include <string>

namespace tmr {

// One COUNT(*) on a database while COLMAP may be writing it (WAL journal:
// readers do not block the writer); -1 when it cannot be read right now.
int64_t CountRows(const std::string& database, const std::string& sql);

// Runs a COLMAP controller thread to its end; about every ten seconds
// reports `count()` of `total` with a rate-based ETA.
void RunWithProgress(colmap::Thread* thread, const std::string& what,
                     const std::function<int64_t()>& count, int64_t total,
                     const std::function<void(const std::string&)>& progress);

}  // namespace tmr
