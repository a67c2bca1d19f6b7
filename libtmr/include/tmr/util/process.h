// Copyright (c) 2026, the tmr authors. BSD-3-Clause.
// Process-wide helpers every stage uses: wall time, memory used and handed
// back.
#pragma once

#include <chrono>
#include <fstream>
#include <string>
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
// /proc/meminfo), or less where a control group limits it or one of its
// parents (a Slurm job's --mem, a container; cgroup v2 memory.max or v1
// memory.limit_in_bytes); 0 where none is known.
double AvailableMemoryMiB();

// The smallest memory limit (MiB) that `file` (memory.max,
// memory.limit_in_bytes) sets for the control group `group` (its path in
// /proc/self/cgroup) under `root` (/sys/fs/cgroup) or for one of its
// parents up to `root`; 0 when none does ("max" sets none).
double SmallestGroupLimitMiB(const std::string& root, const std::string& group,
                             const std::string& file);

}  // namespace tmr
