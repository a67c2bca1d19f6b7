// Copyright (c) 2026, the tmr authors. BSD-3-Clause.
#include "tmr/util/process.h"

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace tmr {
namespace fs = std::filesystem;

double SmallestGroupLimitMiB(const std::string& root, const std::string& group,
                             const std::string& file) {
  double smallest = 0.0;
  const fs::path top = fs::path(root).lexically_normal();
  const fs::path relative = fs::path(group).relative_path().lexically_normal();
  fs::path folder = relative.empty() || relative == "." ? top : top / relative;
  while (true) {
    std::ifstream limit(folder / file);
    double bytes = 0.0;
    if (limit >> bytes && bytes > 0.0) {
      const double mib = bytes / (1024.0 * 1024.0);
      if (smallest <= 0.0 || mib < smallest) smallest = mib;
    }
    if (folder == top || !folder.has_parent_path() ||
        folder.parent_path() == folder)
      break;
    folder = folder.parent_path();
  }
  return smallest;
}

double AvailableMemoryMiB() {
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
  // /proc/self/cgroup: "hierarchy:controllers:path" per line; "0::path" is
  // cgroup v2, a line whose controllers name "memory" the v1 memory group.
  std::ifstream groups("/proc/self/cgroup");
  std::string line;
  while (std::getline(groups, line)) {
    const size_t first = line.find(':');
    const size_t second = line.find(':', first + 1);
    if (first == std::string::npos || second == std::string::npos) continue;
    const std::string controllers = line.substr(first + 1, second - first - 1);
    const std::string path = line.substr(second + 1);
    double limit = 0.0;
    if (line.compare(0, first, "0") == 0 && controllers.empty()) {
      limit = SmallestGroupLimitMiB("/sys/fs/cgroup", path, "memory.max");
    } else {
      std::istringstream names(controllers);
      std::string name;
      while (std::getline(names, name, ',')) {
        if (name == "memory") {
          limit = SmallestGroupLimitMiB("/sys/fs/cgroup/memory", path,
                                        "memory.limit_in_bytes");
        }
      }
    }
    if (limit > 0.0 && (mib <= 0.0 || limit < mib)) mib = limit;
  }
  return mib;
}

}  // namespace tmr
