// Copyright (c) 2026, the tmr authors. BSD-3-Clause.
// Progress of COLMAP's extraction and matching threads, read from the
// database they write, and of work that cannot count its steps.
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
// reports `count()` of `total` with a rate-based ETA. With
// `total_is_bound` the total is an upper bound (pairs that retrieval may
// find twice) and the line says "at most" for both.
void RunWithProgress(colmap::Thread* thread, const std::string& what,
                     const std::function<int64_t()>& count, int64_t total,
                     bool total_is_bound,
                     const std::function<void(const std::string&)>& progress);

// Runs `work` on its own thread to its end, for work that cannot count
// what it has done (a vocabulary's k-means); about every ten seconds
// reports "`what`: N s so far". Returns what `work` returns.
bool RunWithHeartbeat(const std::function<bool()>& work,
                      const std::string& what,
                      const std::function<void(const std::string&)>& progress);

}  // namespace tmr
