// Copyright (c) 2026, the tmr authors. BSD-3-Clause.
// Process-wide helpers every stage uses: wall time, memory used and handed
// back.
#pragma once

#include <chrono>
#include <fstream>
#include <string>
#include <vector>
#if defined(__GLIBC__)
#include <malloc.h>
#endif

namespace tmr {

// Seconds of wall time since `start`.
inline double SecondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start)
      .count();
}

// Hands memory that was freed back to the system (glibc keeps freed memory
// in per-thread arenas: an adjustment run on another worker thread than the
// previous one would otherwise add to the peak). A no-op elsewhere.
inline void ReleaseFreedMemory() {
#if defined(__GLIBC__)
  malloc_trim(0);
#endif
}

// Resident memory of this process now (VmRSS) and at its peak so far
// (VmHWM), in MiB, from /proc/self/status; zeros where there is none.
struct ProcessMemory {
  double rss_mib = 0.0;
  double peak_mib = 0.0;
};
inline ProcessMemory ReadProcessMemory() {
  ProcessMemory memory;
  std::ifstream status("/proc/self/status");
  std::string key;
  double kib = 0.0;
  while (status >> key) {
    if (key == "VmRSS:" && status >> kib) memory.rss_mib = kib / 1024;
    if (key == "VmHWM:" && status >> kib) memory.peak_mib = kib / 1024;
  }
  return memory;
}

// The memory this process may use, in MiB: the machine's (MemTotal of
// /proc/meminfo), or less where a control group limits it (a Slurm job's
// --mem, a container); 0 where none is known.
inline double AvailableMemoryMiB() {
  double mib = 0.0;
  std::ifstream meminfo("/proc/meminfo");
  std::string key;
  double kib = 0.0;
  while (meminfo >> key) {
    if (key == "MemTotal:" && meminfo >> kib) {
      mib = kib / 1024;
      break;
    }
  }
  // The limit of this process's control group: cgroup v2 (the group's
  // path in /proc/self/cgroup, "0::/path"), else v1; "max" or a huge
  // number means none.
  std::vector<std::string> limits;
  std::ifstream groups("/proc/self/cgroup");
  std::string line;
  while (std::getline(groups, line)) {
    if (line.rfind("0::", 0) == 0)
      limits.push_back("/sys/fs/cgroup" + line.substr(3) + "/memory.max");
  }
  limits.push_back("/sys/fs/cgroup/memory.max");
  limits.push_back("/sys/fs/cgroup/memory/memory.limit_in_bytes");
  for (const std::string& path : limits) {
    std::ifstream limit(path);
    double bytes = 0.0;
    if (limit >> bytes && bytes > 0.0) {
      const double limit_mib = bytes / (1024.0 * 1024.0);
      if (mib <= 0.0 || limit_mib < mib) mib = limit_mib;
    }
  }
  return mib;
}

}  // namespace tmr
