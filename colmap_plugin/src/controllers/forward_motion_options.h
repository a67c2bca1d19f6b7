// Copyright (c) 2026, the tmr authors. BSD-3-Clause.
// The mapper's settings for photos taken moving straight ahead
// (sfm/forward_motion.h measures whether they do).
#pragma once

#include "tmr/colmap/tmr_mapper.h"

namespace tmr {

// COLMAP's mapper options for photos taken moving straight ahead
// (docs/reconstruct.md, "Photos taken walking straight ahead"): the
// initial pair may move forward and see its points under 2 degrees, points
// are triangulated and kept down to 0.5 degrees, and with `keep_intrinsics`
// (every camera has an EXIF focal length) the focal length and distortion
// stay at their priors, which forward motion cannot tell from depth.
// Options that differ from COLMAP's defaults in `options` (set by the
// user) are kept.
MapperPassThroughOptions ForwardMotionMapperOptions(
    const MapperPassThroughOptions& options, bool keep_intrinsics);

}  // namespace tmr
