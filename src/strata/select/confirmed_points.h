#pragma once
// What a keyframe confirmed: the surface points where its measured depth
// agrees with the map it was scored against. Change detection carries the latest observations
// forward into the session's own layer around these points (change/carry_forward.h), so an
// object that stands as it stood before is in that session's layer although none (or too few) of
// its images were fused.
//
// A sample confirms when its ray hit the map, the map holds the measured point (the raycast's
// surface check) and the measured depth lies within `depth_tolerance_m` of the rendered one and
// within the fusion's range. The point is the measured one; it vouches for a ball of
// radius_scale x the sample spacing at its depth (stride x depth / fx), at least min_radius_m.
// Thread safe (pure functions).
#include <vector>

#include "strata/change/carry_forward.h"
#include "strata/core/types.h"
#include "strata/select/select_samples.h"

namespace strata::selection {

struct ConfirmConfig {
  /// Off by default: only the incremental loop with change detection needs the points.
  bool enabled = false;
  /// |measured - rendered| at most this (the selection map's voxel plus sensor noise at 4 m).
  float depth_tolerance_m = 0.1f;
  /// Measured depth beyond this confirms nothing: fusion does not use it.
  float max_depth_m = 5.0f;
  /// 0.75 x the spacing covers the diagonal gap between neighbouring samples (0.71).
  float radius_scale = 0.75f;
  /// At least the band where a session's layer can differ from the static map: 2 voxels at 2 cm.
  float min_radius_m = 0.04f;

  void validate() const;  // InputError naming the field
};

/// The confirmed points of one scored keyframe (see above), world frame. `samples`: its raycast
/// with surface checks; `frame`: its depth and pose.
std::vector<change::ConfirmedPoint> confirmedPoints(const SampleRaycast& samples,
                                                    const RgbdFrame& frame,
                                                    const CameraIntrinsics& intrinsics,
                                                    const ConfirmConfig& config);

}  // namespace strata::selection
