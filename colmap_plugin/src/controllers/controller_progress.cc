// Copyright (c) 2026, the tmr authors. BSD-3-Clause.
#include "controllers/controller_progress.h"

#include <algorithm>
#include <chrono>
#include <future>
#include <iomanip>
#include <sstream>
#include <thread>

#include "tmr/io/database_reader.h"
#include "tmr/io/sqlite.h"
#include "tmr/util/process.h"

namespace tmr {

using Clock = std::chrono::steady_clock;

int64_t CountRows(const std::string& database, const std::string& sql) {
  try {
    const SqliteDatabase db(database, SqliteDatabase::Mode::kReadOnly,
                            /*busy_timeout_ms=*/1000);
    SqliteStatement stmt(db, sql);
    return stmt.Step() ? stmt.Int(0) : -1;
  } catch (const DatabaseError&) {
    return -1;
  }
}

void RunWithProgress(colmap::Thread* thread, const std::string& what,
                     const std::function<int64_t()>& count, int64_t total,
                     bool total_is_bound,
                     const std::function<void(const std::string&)>& progress) {
  const std::string bound = total_is_bound ? "at most " : "";
  const auto start = Clock::now();
  const int64_t initial = std::max<int64_t>(0, count());
  thread->Start();
  auto last = start;
  while (!thread->IsFinished()) {
    std::this_thread::sleep_for(std::chrono::milliseconds(200));
    if (!progress || Clock::now() - last < std::chrono::seconds(10)) continue;
    last = Clock::now();
    const int64_t done = count();
    if (done < 0) continue;
    std::ostringstream line;
    line << what << ": " << done << " of " << bound << total;
    const double seconds = SecondsSince(start);
    if (done > initial && done < total) {
      line << "; ETA " << bound << std::fixed << std::setprecision(0)
           << seconds / (done - initial) * (total - done) << " s";
    }
    progress(line.str());
  }
  thread->Wait();
}

bool RunWithHeartbeat(const std::function<bool()>& work,
                      const std::string& what,
                      const std::function<void(const std::string&)>& progress) {
  const auto start = Clock::now();
  std::future<bool> result = std::async(std::launch::async, work);
  while (result.wait_for(std::chrono::seconds(10)) !=
         std::future_status::ready) {
    if (progress) {
      progress(what + ": " +
               std::to_string(static_cast<int>(SecondsSince(start))) +
               " s so far");
    }
  }
  return result.get();
}

}  // namespace tmr
