// Copyright (c) 2026, the tmr authors. BSD-3-Clause.
#include "tmr/util/process.h"

#include <gtest/gtest.h>

#include <vector>

namespace tmr {
namespace {

TEST(ProcessMemory, PeakFollowsWhatTheProcessTouched) {
  const ProcessMemory before = ReadProcessMemory();
  ASSERT_GT(before.rss_mib, 0.0);  // Linux: /proc/self/status
  EXPECT_GE(before.peak_mib, before.rss_mib);
  std::vector<char> block(256 << 20, 1);  // 256 MiB, every page written
  const ProcessMemory during = ReadProcessMemory();
  EXPECT_GE(during.rss_mib, before.rss_mib + 200) << int(block[12345]);
  EXPECT_GE(during.peak_mib, during.rss_mib);
}

}  // namespace
}  // namespace tmr
