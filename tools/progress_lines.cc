// Copyright (c) 2026, the tmr authors. BSD-3-Clause.
#include "progress_lines.h"

#include <chrono>
#include <iomanip>
#include <iostream>

namespace tmr {

std::function<void(const std::string&)> TimedProgressLines() {
  const auto start = std::chrono::steady_clock::now();
  return [start](const std::string& line) {
    const double t =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start)
            .count();
    std::cout << "[tmr " << std::fixed << std::setprecision(1) << std::setw(7)
              << t << " s] " << line << std::endl;
  };
}

}  // namespace tmr
