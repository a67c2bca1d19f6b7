// Copyright (c) 2026, the tmr authors. BSD-3-Clause.
#pragma once

#include <colmap/scene/database.h>

namespace tmr {

// How the verified pairs of a database move: photos taken walking or
// driving straight ahead move along their viewing direction, which
// COLMAP's initial-pair test refuses (init_max_forward_motion: at most
// 95% of the motion along the optical axis) and which gives small
// triangulation angles.
struct ForwardMotionStats {
  int num_pairs = 0;    // verified pairs with an essential or fundamental
                        // matrix (calibrated or uncalibrated configuration)
  int num_forward = 0;  // of those, moving along the viewing direction
  int num_cameras = 0;
  int num_cameras_with_prior_focal = 0;  // focal length from EXIF

  // More than `share` of the pairs move forward (0.5: most of them).
  bool MovesForward(double share) const {
    return num_forward > share * num_pairs;
  }
};

// Counts the pairs whose translation direction t (of cam2_from_cam1) has
// |t_z| > max_forward_motion * |t|, COLMAP's forward-motion test of the
// initial pair. t spans the left null space of E, or of K2^-T F K1^-1 when
// only F was estimated (the epipole in image 2 through camera 2's focal
// length and principal point; distortion is ignored).
ForwardMotionStats MeasureForwardMotion(const colmap::Database& database,
                                        double max_forward_motion);

}  // namespace tmr
