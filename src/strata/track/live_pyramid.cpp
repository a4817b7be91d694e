#include "strata/track/live_pyramid.h"

#include <algorithm>
#include <cmath>

#include "strata/integrate/normal_estimation.h"
#include "strata/map/camera_math.h"

namespace strata {
namespace {

LiveLevel makeLevel(DepthImage depth, const CameraIntrinsics& intrinsics, const MapConfig& map) {
  LiveLevel level;
  level.intrinsics = intrinsics;
  const FrameCamera camera = FrameCamera::from(intrinsics, Eigen::Isometry3d::Identity());
  level.normal_C = estimateNormalsReference(depth, camera, map);
  level.vertex_C.assign(depth.depth_m.size(), Eigen::Vector4f::Zero());
  for (int v = 0; v < depth.height_px; ++v) {
    for (int u = 0; u < depth.width_px; ++u) {
      const std::size_t i = static_cast<std::size_t>(v) * depth.width_px + u;
      const float d = depth.depth_m[i];
      if (!depthValid(d, map.min_depth_m, map.max_depth_m)) {
        level.normal_C[i].setZero();
        continue;
      }
      const Eigen::Vector3f p =
          pixelRay(static_cast<float>(u), static_cast<float>(v), camera.K) * d;
      level.vertex_C[i] = Eigen::Vector4f(p.x(), p.y(), p.z(), 1.0f);
      if (level.normal_C[i].w() > 0.5f) ++level.valid;
    }
  }
  level.depth = std::move(depth);
  return level;
}

}  // namespace

CameraIntrinsics halfIntrinsics(const CameraIntrinsics& in) {
  CameraIntrinsics out = in;
  out.width_px = in.width_px / 2;
  out.height_px = in.height_px / 2;
  out.fx_px = in.fx_px * 0.5f;
  out.fy_px = in.fy_px * 0.5f;
  out.cx_px = (in.cx_px + 0.5f) * 0.5f - 0.5f;
  out.cy_px = (in.cy_px + 0.5f) * 0.5f - 0.5f;
  return out;
}

DepthImage halfDepth(const DepthImage& depth, const MapConfig& map, float threshold_m) {
  DepthImage out(depth.width_px / 2, depth.height_px / 2);
  for (int v = 0; v < out.height_px; ++v) {
    for (int u = 0; u < out.width_px; ++u) {
      float samples[4];
      int n = 0;
      for (int dv = 0; dv < 2; ++dv) {
        for (int du = 0; du < 2; ++du) {
          const float d = depth.at(2 * u + du, 2 * v + dv);
          if (depthValid(d, map.min_depth_m, map.max_depth_m)) samples[n++] = d;
        }
      }
      if (n == 0) continue;
      const float nearest = *std::min_element(samples, samples + n);
      float sum = 0.0f;
      int used = 0;
      for (int k = 0; k < n; ++k) {
        if (samples[k] - nearest <= threshold_m) {
          sum += samples[k];
          ++used;
        }
      }
      out.at(u, v) = sum / static_cast<float>(used);
    }
  }
  return out;
}

std::vector<LiveLevel> buildLivePyramid(const DepthImage& depth, const CameraIntrinsics& intrinsics,
                                        const MapConfig& map, int levels, float threshold_m) {
  std::vector<LiveLevel> pyramid;
  pyramid.reserve(static_cast<std::size_t>(levels));
  DepthImage current = depth;
  CameraIntrinsics current_intrinsics = intrinsics;
  for (int l = 0; l < levels; ++l) {
    DepthImage next;
    CameraIntrinsics next_intrinsics;
    if (l + 1 < levels) {
      next = halfDepth(current, map, threshold_m);
      next_intrinsics = halfIntrinsics(current_intrinsics);
    }
    pyramid.push_back(makeLevel(std::move(current), current_intrinsics, map));
    current = std::move(next);
    current_intrinsics = next_intrinsics;
  }
  return pyramid;
}

}  // namespace strata
