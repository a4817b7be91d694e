#include "strata/select/changed_views.h"

#include <algorithm>
#include <cmath>
#include <unordered_set>
#include <utility>

#include "strata/core/error.h"
#include "strata/map/camera_math.h"

namespace strata::selection {

void ChangedViewConfig::validate() const {
  if (!(depth_tolerance_m > 0.0f) || !std::isfinite(depth_tolerance_m)) {
    throw InputError("changed views: depth_tolerance_m must be a positive number");
  }
  if (!(max_depth_m > depth_tolerance_m) || !std::isfinite(max_depth_m)) {
    throw InputError("changed views: max_depth_m must be a number above depth_tolerance_m");
  }
}

namespace {

/// passesPoint with the frame's T_C_W computed once by the caller.
bool passes(const RgbdFrame& frame, const Eigen::Isometry3f& T_C_W, const CameraIntrinsics& k,
            const Eigen::Vector3f& point_W, const ChangedViewConfig& config) {
  const Eigen::Vector3f p_C = T_C_W * point_W;
  if (!(p_C.z() > 0.0f)) return false;
  const int u = static_cast<int>(std::lround(k.fx_px * p_C.x() / p_C.z() + k.cx_px));
  const int v = static_cast<int>(std::lround(k.fy_px * p_C.y() / p_C.z() + k.cy_px));
  if (u < 0 || v < 0 || u >= k.width_px || v >= k.height_px) return false;
  const float measured_m = frame.depth.at(u, v);
  return measured_m > p_C.z() + config.depth_tolerance_m && measured_m <= config.max_depth_m;
}

/// Per sample: 1 where its ray hit the map and the keyframe measures beyond the map's surface
/// (by more than the tolerance, within the fusion's range).
std::vector<std::uint8_t> samplesBeyond(const SampleRaycast& samples, const RgbdFrame& frame,
                                        const ChangedViewConfig& config) {
  const SampleGrid& grid = samples.grid;
  std::vector<std::uint8_t> beyond(static_cast<std::size_t>(grid.count()), 0);
  for (int gy = 0; gy < grid.height; ++gy) {
    for (int gx = 0; gx < grid.width; ++gx) {
      const std::size_t s = static_cast<std::size_t>(gy) * grid.width + gx;
      if (!samples.hit.at(s)) continue;
      const float measured_m = frame.depth.at(grid.pixelU(gx), grid.pixelV(gy));
      // No depth, not beyond the map's surface, or beyond what fusion uses.
      if (!(measured_m > samples.depth_m.at(s) + config.depth_tolerance_m)) continue;
      beyond[s] = measured_m <= config.max_depth_m ? 1 : 0;
    }
  }
  return beyond;
}

}  // namespace

change::ChangedView changedView(const SampleRaycast& samples, const RgbdFrame& frame,
                                const ChangedViewConfig& config) {
  const SampleGrid& grid = samples.grid;
  const std::vector<std::uint8_t> beyond = samplesBeyond(samples, frame, config);
  change::ChangedView view{frame.T_W_C.cast<float>(), {}, change::DepthTiles(grid.stride_px), {}};
  for (int gy = 0; gy < grid.height; ++gy) {
    for (int gx = 0; gx < grid.width; ++gx) {
      const std::size_t s = static_cast<std::size_t>(gy) * grid.width + gx;
      const int u = grid.pixelU(gx), v = grid.pixelV(gy);
      if (beyond[s]) {
        view.samples.push_back({u, v, samples.depth_m[s]});
        continue;
      }
      // Arrived: the keyframe measures a surface (within the fusion's range) in front of the
      // map's, or where its ray meets none.
      const float measured_m = frame.depth.at(u, v);
      if (!(measured_m > 0.0f) || !(measured_m <= config.max_depth_m)) continue;
      if (samples.hit[s] && !(measured_m < samples.depth_m[s] - config.depth_tolerance_m)) continue;
      view.arrived.push_back({u, v, measured_m});
    }
  }
  return view;
}

namespace {

/// A sample's place in a view: its cell and 10 cm of depth.
std::uint64_t placeKey(int u_px, int v_px, float surface_m, int stride_px) {
  const auto cell_u = static_cast<std::uint64_t>(u_px / stride_px) & 0xFFFFu;
  const auto cell_v = static_cast<std::uint64_t>(v_px / stride_px) & 0xFFFFu;
  const auto depth_bin = static_cast<std::uint64_t>(std::max(0.0f, surface_m) * 10.0f) & 0xFFFFu;
  return cell_u | cell_v << 16 | depth_bin << 32;
}

}  // namespace

std::size_t shareVacatedPlaces(std::vector<change::ChangedView>& views,
                               const std::vector<RgbdFrame>& frames,
                               const std::vector<std::uint8_t>& targets,
                               const CameraIntrinsics& intrinsics, const ChangedViewConfig& config,
                               int stride_px) {
  config.validate();
  if (views.size() != frames.size() || targets.size() != frames.size()) {
    throw InputError("shareVacatedPlaces: " + std::to_string(views.size()) + " views, " +
                     std::to_string(frames.size()) + " frames and " +
                     std::to_string(targets.size()) + " targets: one each per keyframe");
  }
  if (stride_px < 1) throw InputError("shareVacatedPlaces: stride_px must be >= 1");
  const Eigen::Vector4f K(intrinsics.fx_px, intrinsics.fy_px, intrinsics.cx_px, intrinsics.cy_px);
  // Every view's samples as world points on the map's surface, with the view they came from.
  std::vector<std::pair<Eigen::Vector3f, std::size_t>> points_W;
  for (std::size_t j = 0; j < views.size(); ++j) {
    for (const Eigen::Vector3f& p : change::samplePoints(views[j], intrinsics)) {
      points_W.emplace_back(p, j);
    }
  }
  std::size_t added = 0;
  for (std::size_t k = 0; k < views.size(); ++k) {
    if (!targets[k]) continue;
    change::ChangedView& view = views[k];
    std::unordered_set<std::uint64_t> places;
    for (const change::VacatedSample& s : view.samples) {
      places.insert(placeKey(s.u_px, s.v_px, s.surface_m, stride_px));
    }
    const Eigen::Isometry3f T_C_W = frames[k].T_W_C.inverse().cast<float>();
    for (const auto& [point_W, source] : points_W) {
      if (source == k || !passes(frames[k], T_C_W, intrinsics, point_W, config)) continue;
      const Eigen::Vector3f p_C = T_C_W * point_W;
      const int u = static_cast<int>(std::lround(K[0] * p_C.x() / p_C.z() + K[2]));
      const int v = static_cast<int>(std::lround(K[1] * p_C.y() / p_C.z() + K[3]));
      // The centre of its cell (as a grid sample with offset stride / 2 would lie).
      const int cell_u = (u / stride_px) * stride_px + stride_px / 2;
      const int cell_v = (v / stride_px) * stride_px + stride_px / 2;
      if (!places.insert(placeKey(cell_u, cell_v, p_C.z(), stride_px)).second) continue;
      view.samples.push_back({cell_u, cell_v, p_C.z()});
      ++added;
    }
  }
  return added;
}

bool passesPoint(const RgbdFrame& frame, const CameraIntrinsics& k, const Eigen::Vector3f& point_W,
                 const ChangedViewConfig& config) {
  return passes(frame, frame.T_W_C.inverse().cast<float>(), k, point_W, config);
}

}  // namespace strata::selection
