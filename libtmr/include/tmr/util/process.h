// Copyright (c) 2026, the tmr authors. BSD-3-Clause.
// Process-wide helpers every stage uses: wall time, and memory handed back.
#pragma once

#include <chrono>
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

}  // namespace tmr
