// Copyright (c) 2026, the tmr authors. BSD-3-Clause.
#include "tmr/util/process.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>
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

TEST(ProcessMemory, AControlGroupLimitsTheProcessAsItsParentsDo) {
  // A Slurm job's limit sits on job_7, the process in job_7/step_0/task_0.
  namespace fs = std::filesystem;
  const fs::path root = fs::path(testing::TempDir()) / "cgroup_test";
  fs::remove_all(root);
  const fs::path task = root / "slurm" / "job_7" / "step_0" / "task_0";
  fs::create_directories(task);
  auto write = [](const fs::path& file, const std::string& text) {
    std::ofstream(file) << text << "\n";
  };
  write(task / "memory.max", "max");
  write(root / "slurm" / "job_7" / "memory.max",
        std::to_string(4LL << 30));  // 4 GiB
  write(root / "slurm" / "memory.max", std::to_string(64LL << 30));
  EXPECT_DOUBLE_EQ(
      SmallestGroupLimitMiB(root.string(), "/slurm/job_7/step_0/task_0",
                            "memory.max"),
      4096.0);
  EXPECT_DOUBLE_EQ(SmallestGroupLimitMiB(root.string(), "/slurm", "memory.max"),
                   65536.0);
  EXPECT_EQ(SmallestGroupLimitMiB(root.string(), "/", "memory.max"), 0.0);
  EXPECT_EQ(SmallestGroupLimitMiB(root.string(), "/other", "memory.max"), 0.0);
  EXPECT_GT(AvailableMemoryMiB(), 0.0);
  fs::remove_all(root);
}

}  // namespace
}  // namespace tmr
