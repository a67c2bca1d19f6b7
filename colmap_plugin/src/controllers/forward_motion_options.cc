// Copyright (c) 2026, the tmr authors. BSD-3-Clause.
#include "controllers/forward_motion_options.h"

namespace tmr {

MapperPassThroughOptions ForwardMotionMapperOptions(
    const MapperPassThroughOptions& options, bool keep_intrinsics) {
  const MapperPassThroughOptions colmap_defaults;
  MapperPassThroughOptions o = options;
  const auto set = [](auto* field, auto default_value, auto value) {
    if (*field == default_value) *field = value;
  };
  set(&o.init_max_forward_motion, colmap_defaults.init_max_forward_motion, 1.0);
  set(&o.init_min_tri_angle, colmap_defaults.init_min_tri_angle, 2.0);
  set(&o.tri_min_angle, colmap_defaults.tri_min_angle, 0.5);
  set(&o.filter_min_tri_angle, colmap_defaults.filter_min_tri_angle, 0.5);
  if (keep_intrinsics) {
    set(&o.ba_refine_focal_length, colmap_defaults.ba_refine_focal_length,
        false);
    set(&o.ba_refine_extra_params, colmap_defaults.ba_refine_extra_params,
        false);
  }
  return o;
}

}  // namespace tmr
