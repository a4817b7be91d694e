// Depth endpoints as obstacles (contract in surface_hits.h).
#include "explore/surface_hits.h"

#include <cmath>
#include <string>

#include "core/error.h"

namespace strata::explore {
namespace {

/// 21 bits per axis, offset so that +-1M cells fit.
std::uint64_t packKey(const Eigen::Vector3i& v) {
  constexpr std::int64_t kOffset = 1 << 20;
  constexpr std::uint64_t kMask = (1u << 21) - 1u;
  return (static_cast<std::uint64_t>(v.x() + kOffset) & kMask) |
         ((static_cast<std::uint64_t>(v.y() + kOffset) & kMask) << 21) |
         ((static_cast<std::uint64_t>(v.z() + kOffset) & kMask) << 42);
}

Eigen::Vector3i cellOf(const Eigen::Vector3f& p, float size_m) {
  return (p / size_m).array().floor().cast<int>();
}

}  // namespace

SurfaceHits::SurfaceHits(const SurfaceHitsConfig& config) : config_(config) {
  if (!(config.voxel_size_m > 0.0f) || !(config.cell_size_m > 0.0f) ||
      !(config.max_depth_m > 0.0f)) {
    throw InputError("SurfaceHitsConfig: voxel_size_m, cell_size_m and max_depth_m must be > 0");
  }
  if (config.min_frames < 1 || config.pixel_stride < 1) {
    throw InputError("SurfaceHitsConfig: min_frames and pixel_stride must be >= 1");
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
  std::vector<Eigen::Vector3f> points_W;
  for (int v = 0; v < depth.height_px; v += config_.pixel_stride) {
    for (int u = 0; u < depth.width_px; u += config_.pixel_stride) {
      const float z = depth.at(u, v);
      if (!(z > 0.0f) || !(z <= config_.max_depth_m)) continue;  // also NaN
      const Eigen::Vector3f p_C((static_cast<float>(u) - intrinsics.cx_px) * z / intrinsics.fx_px,
                                (static_cast<float>(v) - intrinsics.cy_px) * z / intrinsics.fy_px,
                                z);
      points_W.push_back(T * p_C);
    }
  }
  addPoints(points_W);
}

void SurfaceHits::addPoints(const std::vector<Eigen::Vector3f>& points_W) {
  const std::int64_t frame = frame_++;
  for (const Eigen::Vector3f& p : points_W) {
    if (!p.allFinite()) continue;
    const Eigen::Vector3i voxel = cellOf(p, config_.voxel_size_m);
    VoxelHits& hits = voxels_[packKey(voxel)];
    hits.sum_W += p;
    ++hits.points;
    if (hits.last_frame == frame) continue;  // one vote per frame
    hits.last_frame = frame;
    if (++hits.frames == config_.min_frames)
      addObstacle(hits.sum_W / static_cast<float>(hits.points));
  }
}

void SurfaceHits::addObstacle(const Eigen::Vector3f& p_W) {
  cells_[packKey(cellOf(p_W, config_.cell_size_m))].push_back(p_W);
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
        const auto it = cells_.find(packKey({x, y, z}));
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
