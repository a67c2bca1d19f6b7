// Copyright (c) 2026, the tmr authors. BSD-3-Clause.
// The mapper options for forward motion keep what the user set.
#include "controllers/forward_motion_options.h"

#include <gtest/gtest.h>

namespace tmr {
namespace {

TEST(ForwardMotionMapperOptionsTest, ChangesOnlyCOLMAPsDefaults) {
  MapperPassThroughOptions user;
  user.init_min_tri_angle = 4.0;  // set by the user: kept
  const MapperPassThroughOptions held = ForwardMotionMapperOptions(user, true);
  EXPECT_EQ(held.init_max_forward_motion, 1.0);
  EXPECT_EQ(held.init_min_tri_angle, 4.0);
  EXPECT_EQ(held.tri_min_angle, 0.5);
  EXPECT_EQ(held.filter_min_tri_angle, 0.5);
  EXPECT_FALSE(held.ba_refine_focal_length);
  EXPECT_FALSE(held.ba_refine_extra_params);

  // Without an EXIF focal length for every camera, the intrinsics are still
  // refined.
  const MapperPassThroughOptions refined =
      ForwardMotionMapperOptions(MapperPassThroughOptions(), false);
  EXPECT_EQ(refined.init_min_tri_angle, 2.0);
  EXPECT_TRUE(refined.ba_refine_focal_length);
  EXPECT_TRUE(refined.ba_refine_extra_params);
}

}  // namespace
}  // namespace tmr
