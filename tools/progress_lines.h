// Copyright (c) 2026, the tmr authors. BSD-3-Clause.
// Progress output of the long-running tools.
#pragma once

#include <functional>
#include <string>

namespace tmr {

// Prints each progress line to stdout as "[tmr    12.3 s] line", timed
// from the call.
std::function<void(const std::string&)> TimedProgressLines();

}  // namespace tmr
