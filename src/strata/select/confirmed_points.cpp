#include "strata/select/confirmed_points.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "strata/core/error.h"
#include "strata/map/camera_math.h"

namespace strata::selection {

void ConfirmConfig::validate() const {
  const auto positive = [](float x) { return x > 0.0f && std::isfinite(x); };
  if (!positive(depth_tolerance_m)) {
    throw InputError("confirm depth_tolerance_m must be a positive number");
  }
  if (!positive(max_depth_m)) throw InputError("confirm max_depth_m must be a positive number");
  if (!(radius_scale >= 0.0f) || !std::isfinite(radius_scale)) {
    throw InputError("confirm radius_scale must be a number >= 0");
  }
  if (!(min_radius_m >= 0.0f) || !std::isfinite(min_radius_m)) {
    throw InputError("confirm min_radius_m must be a number >= 0");
  }
}

std::vector<change::ConfirmedPoint> confirmedPoints(const SampleRaycast& samples,
                                                    const RgbdFrame& frame,
                                                    const CameraIntrinsics& k,
                                                    const ConfirmConfig& config) {
  const SampleGrid& grid = samples.grid;
  const std::size_t n = static_cast<std::size_t>(grid.count());
  if (samples.hit.size() != n || samples.depth_m.size() != n || samples.surface.size() != n) {
    throw InputError("confirmedPoints: keyframe '" + frame.name +
                     "': the raycast lacks hits, depths or surface checks for its grid");
  }
  const Eigen::Vector4f K(k.fx_px, k.fy_px, k.cx_px, k.cy_px);
  const Eigen::Isometry3f T_W_C = frame.T_W_C.cast<float>();
  std::vector<change::ConfirmedPoint> points;
  for (int gy = 0; gy < grid.height; ++gy) {
    for (int gx = 0; gx < grid.width; ++gx) {
      const std::size_t s = static_cast<std::size_t>(gy) * grid.width + gx;
      if (!samples.hit[s] || samples.surface[s] != SurfaceCheck::kHeld) continue;
      const int u = grid.pixelU(gx), v = grid.pixelV(gy);
      const float measured_m = frame.depth.at(u, v);
      if (!(measured_m > 0.0f) || measured_m > config.max_depth_m) continue;
      if (!(std::fabs(measured_m - samples.depth_m[s]) <= config.depth_tolerance_m)) continue;
      const Eigen::Vector3f ray_C = pixelRay(static_cast<float>(u), static_cast<float>(v), K);
      change::ConfirmedPoint point;
      point.p_W = T_W_C * Eigen::Vector3f(ray_C * measured_m);
      const float spacing_m = static_cast<float>(grid.stride_px) * measured_m / k.fx_px;
      point.radius_m = std::max(config.radius_scale * spacing_m, config.min_radius_m);
      points.push_back(point);
    }
  }
  return points;
}

}  // namespace strata::selection
