// Copyright (c) 2026, the tmr authors. BSD-3-Clause.
#include "tmr/scene/match_graph.h"

#include <algorithm>

namespace tmr {

int MatchGraph::FindImageIndex(uint32_t image_id) const {
  const auto it =
      std::lower_bound(images.begin(), images.end(), image_id,
                       [](const MatchGraphImage& image, uint32_t id) {
                         return image.image_id < id;
                       });
  if (it == images.end() || it->image_id != image_id) return -1;
  return static_cast<int>(it - images.begin());
}

}  // namespace tmr
