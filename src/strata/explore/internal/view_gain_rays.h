#pragma once
// The fixed-point ray fan shared by the view gain kernel and its reference, so both march the same
// voxels and add the same integers (results agree bit for bit). Internal to strata::explore.
//
// Positions are in 1/256 voxel units: a position is its voxel plus a fraction in [0, 256). A ray's
// direction is quantised to 1/8192; step k's distance t_k to 1/256 voxel. The offset of step k is
// (dir_q * t_q[k]) >> 13 (32-bit product: rays of at most kMaxRayVoxels keep it below 2^30;
// arithmetic shift = floor), the voxel of step k is origin_voxel + ((origin_frac + offset) >> 8).
// Volumes are integers of `unit_m3`.
#include <Eigen/Core>
#include <cstdint>
#include <vector>

#include "strata/explore/view_gain.h"

namespace strata::explore::internal {

inline constexpr int kFracBits = 8;  // position: 1/256 voxel
inline constexpr int kDirBits = 13;  // direction: 1/8192
/// |position / voxel| must stay below this (positions outside are an InputError).
inline constexpr double kMaxVoxelCoord = 4.0e6;
/// Rays reach at most this many voxels (max_range_m / voxel_size_m): the product above fits 32
/// bits, and the device's block table around one position stays small.
inline constexpr double kMaxRayVoxels = 512.0;

struct ViewGainRays {
  float voxel_size_m = 0.0f;
  double unit_m3 = 0.0;       // volume of one weight unit
  int bin_rays = 0;           // rays per yaw bin: rays_per_bin x elevation_rays of the config
  int rays_per_position = 0;  // yaw_bins x bin_rays
  int steps = 0;              // samples per ray
  /// Ray r = (bin * config.rays_per_bin + column) * elevation_rays + row: x, y, z, row.
  std::vector<Eigen::Vector4i> dir_q;
  /// Per step: distance of its sample from the position, 1/256 voxel.
  std::vector<std::int32_t> t_q;
  /// Per (row, step), row * steps + step: the volume a ray of that row stands for at that step.
  std::vector<std::uint32_t> weight;
};

/// The fan of `config` on a map of `voxel_size_m`. InputError when the rays would be longer than
/// kMaxRayVoxels voxels.
ViewGainRays makeViewGainRays(const ViewGainConfig& config, float voxel_size_m);

/// A position in fixed point: voxel and fraction (1/256). InputError for non-finite positions or
/// positions beyond kMaxVoxelCoord voxels.
struct FixedPosition {
  Eigen::Vector3i voxel;
  Eigen::Vector3i frac;
};
FixedPosition fixedPosition(const Eigen::Vector3f& p_W, float voxel_size_m);

/// The voxel of step `step` of ray `ray` from `origin`.
inline Eigen::Vector3i stepVoxel(const FixedPosition& origin, const Eigen::Vector4i& dir_q,
                                 std::int32_t t_q) {
  Eigen::Vector3i v;
  for (int a = 0; a < 3; ++a) {
    const std::int32_t offset = (dir_q[a] * t_q) >> kDirBits;
    v[a] = origin.voxel[a] + ((origin.frac[a] + offset) >> kFracBits);
  }
  return v;
}

/// Observed and occupied: the march stops there. `occupied_below_m` is half a voxel (float).
inline bool stopsRay(float tsdf_m, float weight, float min_weight, float occupied_below_m) {
  return weight >= min_weight && tsdf_m < occupied_below_m;
}

/// The blocks every sample of the fan from one position lies in: [lo, hi] per axis, inclusive.
struct BlockBox {
  Eigen::Vector3i lo, hi;
  std::int64_t blocks() const {
    return (hi - lo + Eigen::Vector3i::Ones()).cast<std::int64_t>().prod();
  }
  BlockBox merged(const BlockBox& o) const { return {lo.cwiseMin(o.lo), hi.cwiseMax(o.hi)}; }
};
BlockBox fanBlocks(const FixedPosition& origin, const ViewGainRays& rays);

/// The ViewGain of one position from its per-bin integer volumes (same code for both paths).
ViewGain finishViewGain(const std::uint64_t* bin_units, const ViewGainRays& rays,
                        const ViewGainConfig& config);

}  // namespace strata::explore::internal
