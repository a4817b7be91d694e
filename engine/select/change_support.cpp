#include "select/change_support.h"

#include <algorithm>
#include <cmath>
#include <unordered_set>
#include <utility>

#include "core/error.h"
#include "map/camera_math.h"

namespace strata::selection {

void SupportConfig::validate() const {
  if (views < 0) throw InputError("support views must be >= 0, got " + std::to_string(views));
  if (min_points < 1) {
    throw InputError("support min_points must be >= 1, got " + std::to_string(min_points));
  }
  if (!(depth_tolerance_m > 0.0f) || !std::isfinite(depth_tolerance_m)) {
    throw InputError("support depth_tolerance_m must be a positive number");
  }
  if (min_neighbours < 0 || min_neighbours > 8) {
    throw InputError("support min_neighbours must be in [0, 8], got " +
                     std::to_string(min_neighbours));
  }
  if (!(max_depth_m > depth_tolerance_m) || !std::isfinite(max_depth_m)) {
    throw InputError("support max_depth_m must be a number above depth_tolerance_m");
  }
}

namespace {

/// passesPoint with the frame's T_C_W computed once by the caller.
bool passes(const RgbdFrame& frame, const Eigen::Isometry3f& T_C_W, const CameraIntrinsics& k,
            const Eigen::Vector3f& point_W, const SupportConfig& config) {
  const Eigen::Vector3f p_C = T_C_W * point_W;
  if (!(p_C.z() > 0.0f)) return false;
  const int u = static_cast<int>(std::lround(k.fx_px * p_C.x() / p_C.z() + k.cx_px));
  const int v = static_cast<int>(std::lround(k.fy_px * p_C.y() / p_C.z() + k.cy_px));
  if (u < 0 || v < 0 || u >= k.width_px || v >= k.height_px) return false;
  const float measured_m = frame.depth.at(u, v);
  return measured_m > p_C.z() + config.depth_tolerance_m && measured_m <= config.max_depth_m;
}

/// Of the 8 grid neighbours of sample (gx, gy), how many look beyond the map's surface.
int neighboursBeyond(const std::vector<std::uint8_t>& beyond, const SampleGrid& grid, int gx,
                     int gy) {
  int n = 0;
  for (int dy = -1; dy <= 1; ++dy) {
    for (int dx = -1; dx <= 1; ++dx) {
      const int x = gx + dx, y = gy + dy;
      if ((dx == 0 && dy == 0) || x < 0 || y < 0 || x >= grid.width || y >= grid.height) continue;
      n += beyond[static_cast<std::size_t>(y) * grid.width + x];
    }
  }
  return n;
}

/// Per sample: 1 where its ray hit the map and the keyframe measures beyond the map's surface
/// (by more than the tolerance, within the fusion's range).
std::vector<std::uint8_t> samplesBeyond(const SampleRaycast& samples, const RgbdFrame& frame,
                                        const SupportConfig& config) {
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
                                const SupportConfig& config) {
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
                               const CameraIntrinsics& intrinsics, const SupportConfig& config,
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

std::vector<Eigen::Vector3f> vacatedPoints(const SampleRaycast& samples, const RgbdFrame& frame,
                                           const CameraIntrinsics& k, const SupportConfig& config) {
  const SampleGrid& grid = samples.grid;
  const Eigen::Vector4f K(k.fx_px, k.fy_px, k.cx_px, k.cy_px);
  const Eigen::Isometry3f T_W_C = frame.T_W_C.cast<float>();
  const std::vector<std::uint8_t> beyond = samplesBeyond(samples, frame, config);
  std::vector<Eigen::Vector3f> points_W;
  for (int gy = 0; gy < grid.height; ++gy) {
    for (int gx = 0; gx < grid.width; ++gx) {
      const std::size_t s = static_cast<std::size_t>(gy) * grid.width + gx;
      if (!beyond[s] || neighboursBeyond(beyond, grid, gx, gy) < config.min_neighbours) continue;
      const int u = grid.pixelU(gx), v = grid.pixelV(gy);
      const Eigen::Vector3f ray_C = pixelRay(static_cast<float>(u), static_cast<float>(v), K);
      points_W.push_back(T_W_C * Eigen::Vector3f(ray_C * samples.depth_m[s]));  // map's surface
    }
  }
  return points_W;
}

bool passesPoint(const RgbdFrame& frame, const CameraIntrinsics& k, const Eigen::Vector3f& point_W,
                 const SupportConfig& config) {
  return passes(frame, frame.T_W_C.inverse().cast<float>(), k, point_W, config);
}

namespace {

/// passed[k][p]: a ray of keyframe k passes point p.
std::vector<std::vector<std::uint8_t>> visibility(const std::vector<Eigen::Vector3f>& points_W,
                                                  const std::vector<RgbdFrame>& frames,
                                                  const CameraIntrinsics& intrinsics,
                                                  const SupportConfig& config) {
  std::vector<std::vector<std::uint8_t>> passed(frames.size());
  for (std::size_t k = 0; k < frames.size(); ++k) {
    const Eigen::Isometry3f T_C_W = frames[k].T_W_C.inverse().cast<float>();
    passed[k].resize(points_W.size());
    for (std::size_t p = 0; p < points_W.size(); ++p) {
      passed[k][p] = passes(frames[k], T_C_W, intrinsics, points_W[p], config) ? 1 : 0;
    }
  }
  return passed;
}

std::size_t countUnsupported(const std::vector<int>& views, int needed) {
  return static_cast<std::size_t>(
      std::count_if(views.begin(), views.end(), [needed](int n) { return n < needed; }));
}

}  // namespace

SupportResult supportViews(const std::vector<std::vector<Eigen::Vector3f>>& vacated_points,
                           const std::vector<RgbdFrame>& frames, const CameraIntrinsics& intrinsics,
                           const std::vector<std::uint8_t>& selected, const SupportConfig& config) {
  config.validate();
  if (vacated_points.size() != frames.size() || selected.size() != frames.size()) {
    throw InputError("supportViews: vacated points, frames and selection differ in length");
  }
  SupportResult r;
  r.added.assign(frames.size(), 0);
  if (config.views == 0) return r;
  std::vector<Eigen::Vector3f> points_W;
  for (std::size_t k = 0; k < frames.size(); ++k) {
    if (selected[k] || config.all_keyframes) {
      points_W.insert(points_W.end(), vacated_points[k].begin(), vacated_points[k].end());
    }
  }
  r.points = points_W.size();
  const auto passed = visibility(points_W, frames, intrinsics, config);
  std::vector<int> views(points_W.size(), 0);
  for (std::size_t k = 0; k < frames.size(); ++k) {
    if (!selected[k]) continue;
    for (std::size_t p = 0; p < points_W.size(); ++p) views[p] += passed[k][p];
  }
  r.unsupported_before = countUnsupported(views, config.views);
  for (;;) {
    std::size_t best = frames.size();
    int best_gain = config.min_points - 1;
    for (std::size_t k = 0; k < frames.size(); ++k) {
      if (selected[k] || r.added[k]) continue;
      int gain = 0;
      for (std::size_t p = 0; p < points_W.size(); ++p)
        gain += passed[k][p] && views[p] < config.views;
      if (gain > best_gain) best = k, best_gain = gain;
    }
    if (best == frames.size()) break;
    r.added[best] = 1;
    for (std::size_t p = 0; p < points_W.size(); ++p) views[p] += passed[best][p];
  }
  r.unsupported_after = countUnsupported(views, config.views);
  return r;
}

}  // namespace strata::selection
