#pragma once
// The occupancy update and the ray traversal, written once for the host; the shaders'
// copies are shaders/common/occupancy_rules.glsl and occupancy_ray.glsl, with the same float
// operations in the same order, so the device equals this reference exactly.
#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <cstdint>

#include "strata/occupancy/occupancy_config.h"

namespace strata {

/// Per-voxel state bits (the state label layer on the device).
inline constexpr std::uint32_t kOccupancyMissThisScan = 1u;  // a ray passed through this frame
inline constexpr std::uint32_t kOccupancyHitThisScan = 2u;   // a ray ended here this frame
inline constexpr std::uint32_t kOccupancyObserved = 4u;      // updated at least once
inline constexpr std::uint32_t kOccupancyScanBits = kOccupancyMissThisScan | kOccupancyHitThisScan;

enum class OccupancyClass : std::uint8_t { kUnknown = 0, kFree = 1, kOccupied = 2 };

/// One update per voxel per scan, as OctoMap's insertPointCloud: a voxel that is both an
/// endpoint and on another ray's way gets the hit only. Log-odds update, Eq. (2):
/// L(n | z_1:t) = L(n | z_1:t-1) + L(n | z_t), then clamped to [l_min, l_max], Eq. (3).
/// An unobserved voxel starts from 0 (p = 0.5). Returns the new log-odds.
inline float occupancyUpdate(std::uint32_t state, float log_odds, const OccupancyLogOdds& l) {
  if ((state & kOccupancyScanBits) == 0u) return log_odds;
  const float previous = (state & kOccupancyObserved) != 0u ? log_odds : 0.0f;
  const float sum = previous + ((state & kOccupancyHitThisScan) != 0u ? l.hit : l.miss);
  return std::min(std::max(sum, l.min), l.max);
}

/// State after the update: observed, scan marks cleared.
inline std::uint32_t occupancyStateAfterUpdate(std::uint32_t state) {
  return (state & kOccupancyScanBits) != 0u ? kOccupancyObserved : state;
}

inline OccupancyClass classifyOccupancy(std::uint32_t state, float log_odds,
                                        const OccupancyLogOdds& l) {
  if ((state & kOccupancyObserved) == 0u) return OccupancyClass::kUnknown;
  return log_odds >= l.occupied ? OccupancyClass::kOccupied : OccupancyClass::kFree;
}

/// Camera and range of one frame in the form the ray kernels take.
struct OccupancyRayCamera {
  float T_W_C[16];  // column-major, as GLSL's mat4
  float K_inv[4];   // 1/fx, 1/fy, cx, cy (host-side reciprocals: no division on device)
  float min_depth_m = 0.0f;
  float max_range_m = 0.0f;
  float inv_voxel_size = 0.0f;  // 1 / voxel edge, per metre
};

/// Ray of one pixel in voxel units (global voxel v covers [v, v + 1) per axis).
struct OccupancyRayEnds {
  Eigen::Vector3f origin_vox;
  Eigen::Vector3f end_vox;
  bool hit = false;  // the sample lies within max range: its voxel gets the hit
};

/// False for an invalid sample (0, NaN, infinite, below min depth). Beyond max range the ray is cut
/// at max_range_m along the optical axis and has no hit (OctoMap's maxrange rule).
/// NOTE: written as separate float products and sums in the shader's order; the reference sources
/// are built without FMA contraction (no -march flags) and the shader marks them `precise`.
inline bool occupancyRayEnds(float u, float v, float depth_m, const OccupancyRayCamera& c,
                             OccupancyRayEnds& out) {
  if (!(depth_m > 0.0f && depth_m >= c.min_depth_m) || std::isinf(depth_m)) return false;
  const float range = std::min(depth_m, c.max_range_m);
  const float x = ((u - c.K_inv[2]) * c.K_inv[0]) * range;
  const float y = ((v - c.K_inv[3]) * c.K_inv[1]) * range;
  const float z = range;
  const float* m = c.T_W_C;
  for (int r = 0; r < 3; ++r) {
    const float p = ((m[r] * x + m[4 + r] * y) + m[8 + r] * z) + m[12 + r];
    out.end_vox[r] = p * c.inv_voxel_size;
    out.origin_vox[r] = m[12 + r] * c.inv_voxel_size;
  }
  out.hit = depth_m <= c.max_range_m;
  return true;
}

/// Voxel traversal from the origin's voxel to the endpoint's voxel (Amanatides & Woo, as OctoMap's
/// computeRayKeys). Crossings t_i = dist_i / |d_i| are compared pairwise as dist_i * |d_j| <=
/// dist_j * |d_i| (no division), kept incrementally (a step on axis i adds |d_j| to its products),
/// and an axis steps only while it differs from the endpoint's, so the walk ends exactly at the
/// endpoint voxel after |end - start|_1 steps. Ties go to the lower axis.
class OccupancyVoxelRay {
 public:
  explicit OccupancyVoxelRay(const OccupancyRayEnds& ends) {
    Eigen::Vector3f dist;
    for (int i = 0; i < 3; ++i) {
      voxel_[i] = static_cast<int>(std::floor(ends.origin_vox[i]));
      end_[i] = static_cast<int>(std::floor(ends.end_vox[i]));
      step_[i] = end_[i] > voxel_[i] ? 1 : (end_[i] < voxel_[i] ? -1 : 0);
      d_[i] = std::abs(ends.end_vox[i] - ends.origin_vox[i]);
      dist[i] =
          std::abs(static_cast<float>(voxel_[i] + (step_[i] > 0 ? 1 : 0)) - ends.origin_vox[i]);
    }
    // Pairs (x,y), (x,z), (y,z): lhs_ holds dist_i |d_j|, rhs_ dist_j |d_i|.
    lhs_ = {dist.x() * d_.y(), dist.x() * d_.z(), dist.y() * d_.z()};
    rhs_ = {dist.y() * d_.x(), dist.z() * d_.x(), dist.z() * d_.y()};
  }
  const Eigen::Vector3i& voxel() const { return voxel_; }
  bool atEnd() const { return voxel_ == end_; }
  /// Steps to the next voxel; call only while !atEnd().
  void advance() {
    const bool open_x = voxel_.x() != end_.x(), open_y = voxel_.y() != end_.y();
    const bool open_z = voxel_.z() != end_.z();
    const bool x = open_x && (!open_y || lhs_[0] <= rhs_[0]) && (!open_z || lhs_[1] <= rhs_[1]);
    const bool y = !x && open_y && (!open_z || lhs_[2] <= rhs_[2]);
    if (x) {
      voxel_.x() += step_.x();
      lhs_[0] += d_.y();
      lhs_[1] += d_.z();
    } else if (y) {
      voxel_.y() += step_.y();
      rhs_[0] += d_.x();
      lhs_[2] += d_.z();
    } else {
      voxel_.z() += step_.z();
      rhs_[1] += d_.x();
      rhs_[2] += d_.y();
    }
  }

 private:
  Eigen::Vector3i voxel_;
  Eigen::Vector3i end_;
  Eigen::Vector3i step_;
  Eigen::Vector3f d_;  // |end - origin| per axis
  Eigen::Vector3f lhs_;
  Eigen::Vector3f rhs_;
};

}  // namespace strata
