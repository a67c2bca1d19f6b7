// Copyright (c) 2026, the tmr authors. BSD-3-Clause.
// Top view of camera centres per model (tmr_eval --top_view; OpenCV).
#pragma once

#include <array>
#include <string>
#include <vector>

namespace tmr {

struct CentreSet {
  std::string label;  // "model 0: 45 images"
  std::vector<std::array<double, 3>> centres;
};

// Draws the reference camera centres as grey rings and each set in its own
// colour (with a legend), seen along the direction in which the reference
// centres spread least (the plane of their two principal axes: the ground
// for a street or a ring of photos). Writes a PNG; false on failure.
bool DrawTopView(const std::vector<std::array<double, 3>>& reference,
                 const std::vector<CentreSet>& sets,
                 const std::string& png_path, int size_px = 1200);

}  // namespace tmr
