// Depth endpoints as obstacles (contract in surface_hits.h).
#include "strata/explore/surface_hits.h"

#include <cmath>
#include <string>

#include "strata/core/error.h"

namespace strata::explore {
namespace {

Eigen::Vector3i cellOf(const Eigen::Vector3f& p, float size_m) {
  return (p / size_m).array().floor().cast<int>();
}

}  // namespace

SurfaceHits::SurfaceHits(const SurfaceHitsConfig& config) : config_(config) {
  if (!(config.voxel_size_m > 0.0f) || !(config.cell_size_m > 0.0f) ||
      !(config.max_depth_m > 0.0f)) {
    throw InputError("SurfaceHitsConfig: voxel_size_m, cell_size_m and max_depth_m must be > 0");
  }
  if (config.min_views < 1 || config.min_views > kMaxViews || config.pixel_stride < 1) {
    throw InputError("SurfaceHitsConfig: min_views must be in [1, " + std::to_string(kMaxViews) +
                     "] and pixel_stride >= 1");
  }
  if (!(config.min_baseline_m >= 0.0f) || !(config.edge_jump_m > 0.0f)) {
    throw InputError("SurfaceHitsConfig: min_baseline_m must be >= 0 and edge_jump_m > 0");
  }
}

void SurfaceHits::addFrame(const DepthImage& depth, const CameraIntrinsics& intrinsics,
                           const Eigen::Isometry3d& T_W_C) {
  if (depth.width_px != intrinsics.width_px || depth.height_px != intrinsics.height_px) {
    throw InputError("SurfaceHits: depth image " + std::to_string(depth.width_px) + "x" +
                     std::to_string(depth.height_px) + " for a camera of " +
                     std::to_string(intrinsics.width_px) + "x" +
                     std::to_string(intrinsics.height_px));
  }
  const Eigen::Isometry3f T = T_W_C.cast<float>();
  const int w = depth.width_px, h = depth.height_px;
  // Behind an edge: a 4-neighbour nearer by more than the jump (the far side, or a flying pixel
  // between the sides). The near side stays: it is the thin structure's own surface.
  auto behindEdge = [&](int u, int v, float z) {
    const int du[4] = {-1, 1, 0, 0}, dv[4] = {0, 0, -1, 1};
    for (int i = 0; i < 4; ++i) {
      const int un = u + du[i], vn = v + dv[i];
      if (un < 0 || vn < 0 || un >= w || vn >= h) continue;
      const float zn = depth.at(un, vn);
      if (zn > 0.0f && z - zn > config_.edge_jump_m) return true;
    }
    return false;
  };
  std::vector<Eigen::Vector3f> points_W;
  for (int v = 0; v < h; v += config_.pixel_stride) {
    for (int u = 0; u < w; u += config_.pixel_stride) {
      const float z = depth.at(u, v);
      if (!(z > 0.0f) || !(z <= config_.max_depth_m) || behindEdge(u, v, z)) continue;  // also NaN
      const Eigen::Vector3f p_C((static_cast<float>(u) - intrinsics.cx_px) * z / intrinsics.fx_px,
                                (static_cast<float>(v) - intrinsics.cy_px) * z / intrinsics.fy_px,
                                z);
      points_W.push_back(T * p_C);
    }
  }
  addPoints(points_W, T.translation());
}

void SurfaceHits::addPoints(const std::vector<Eigen::Vector3f>& points_W,
                            const Eigen::Vector3f& camera_W) {
  const float baseline2 = config_.min_baseline_m * config_.min_baseline_m;
  for (const Eigen::Vector3f& p : points_W) {
    if (!p.allFinite()) continue;
    const Eigen::Vector3i voxel = cellOf(p, config_.voxel_size_m);
    VoxelHits& hits = voxels_[voxel];
    if (hits.views >= config_.min_views) continue;  // already an obstacle
    hits.sum_W += p;
    ++hits.points;
    bool new_view = true;
    for (int i = 0; i < hits.views; ++i) {
      if ((hits.views_W[static_cast<std::size_t>(i)] - camera_W).squaredNorm() < baseline2) {
        new_view = false;
      }
    }
    if (!new_view) continue;
    hits.views_W[static_cast<std::size_t>(hits.views++)] = camera_W;
    if (hits.views == config_.min_views) addObstacle(hits.sum_W / static_cast<float>(hits.points));
  }
}

void SurfaceHits::addObstacle(const Eigen::Vector3f& p_W) {
  cells_[cellOf(p_W, config_.cell_size_m)].push_back(p_W);
  ++obstacle_count_;
}

bool SurfaceHits::blocks(const Eigen::Vector3f& centre_W, float radius_m) const {
  if (obstacle_count_ == 0) return false;
  const float reach_m = radius_m;
  const float reach2 = reach_m * reach_m;
  const Eigen::Vector3i lo = cellOf(centre_W.array() - reach_m, config_.cell_size_m);
  const Eigen::Vector3i hi = cellOf(centre_W.array() + reach_m, config_.cell_size_m);
  for (int z = lo.z(); z <= hi.z(); ++z) {
    for (int y = lo.y(); y <= hi.y(); ++y) {
      for (int x = lo.x(); x <= hi.x(); ++x) {
        const auto it = cells_.find(Eigen::Vector3i(x, y, z));
        if (it == cells_.end()) continue;
        for (const Eigen::Vector3f& c : it->second) {
          if ((c - centre_W).squaredNorm() <= reach2) return true;
        }
      }
    }
  }
  return false;
}

std::vector<std::uint8_t> HitGuardedChecker::spheresFree(
    const std::vector<Eigen::Vector3f>& centres_W, float radius_m, UnknownPolicy unknown) {
  std::vector<std::uint8_t> free = inner_->spheresFree(centres_W, radius_m, unknown);
  spheres_tested_ += centres_W.size();
  for (std::size_t i = 0; i < centres_W.size(); ++i) {
    if (free[i] && hits_->blocks(centres_W[i], radius_m)) {
      free[i] = 0;
      ++refused_by_hits_;
    }
  }
  return free;
}

}  // namespace strata::explore
