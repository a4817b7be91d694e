#include "strata/explore/internal/view_gain_rays.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "strata/core/error.h"

namespace strata::explore::internal {
namespace {

constexpr double kTwoPi = 2.0 * M_PI;
// The largest step volume is this many units: quantisation costs ~1e-7 of it per sample.
constexpr double kUnitsOfLargestStep = double(1 << 24);

Eigen::Vector4i quantisedDirection(double yaw_rad, double elevation_rad, int row) {
  const double scale = double(1 << kDirBits);
  const double c = std::cos(elevation_rad);
  return Eigen::Vector4i(static_cast<int>(std::llround(c * std::cos(yaw_rad) * scale)),
                         static_cast<int>(std::llround(c * std::sin(yaw_rad) * scale)),
                         static_cast<int>(std::llround(std::sin(elevation_rad) * scale)), row);
}

std::string tooLong(const ViewGainConfig& config, float voxel_size_m) {
  std::ostringstream out;
  out << "ViewGainConfig.max_range_m: " << config.max_range_m << " m on " << voxel_size_m
      << " m voxels gives rays over " << kMaxRayVoxels << " voxels long";
  return out.str();
}

}  // namespace

ViewGainRays makeViewGainRays(const ViewGainConfig& config, float voxel_size_m) {
  config.validate();
  if (!(voxel_size_m > 0.0f) || !std::isfinite(voxel_size_m)) {
    throw InputError("view gain: the map's voxel size must be positive");
  }
  if (config.max_range_m / voxel_size_m > kMaxRayVoxels) {
    throw InputError(tooLong(config, voxel_size_m));
  }
  const double step_m = double(config.step_voxels) * voxel_size_m;
  const double span_m = double(config.max_range_m) - config.min_range_m;
  const double steps = std::max(1.0, std::ceil(span_m / step_m - 1e-9));

  ViewGainRays rays;
  rays.voxel_size_m = voxel_size_m;
  rays.steps = static_cast<int>(steps);
  rays.bin_rays = config.rays_per_bin * config.elevation_rays;
  rays.rays_per_position = config.yaw_bins * rays.bin_rays;

  const int rows = config.elevation_rays;
  const double bin_rad = kTwoPi / config.yaw_bins;
  const double column_rad = bin_rad / config.rays_per_bin;
  const double row_rad = double(config.vertical_fov_rad) / rows;
  const double bottom_rad = -0.5 * double(config.vertical_fov_rad);
  for (int b = 0; b < config.yaw_bins; ++b) {
    for (int j = 0; j < config.rays_per_bin; ++j) {
      const double yaw = (b + (j + 0.5) / config.rays_per_bin) * bin_rad;
      for (int e = 0; e < rows; ++e) {
        rays.dir_q.push_back(quantisedDirection(yaw, bottom_rad + (e + 0.5) * row_rad, e));
      }
    }
  }

  // Shell k is [a, b]: its sample at the middle, its volume per ray solid angle x (b^3 - a^3) / 3.
  std::vector<double> volume(static_cast<std::size_t>(rows) * rays.steps);
  double largest = 0.0;
  for (int k = 0; k < rays.steps; ++k) {
    const double a = config.min_range_m + k * step_m;
    const double b = std::min<double>(a + step_m, config.max_range_m);
    rays.t_q.push_back(static_cast<std::int32_t>(
        std::llround(0.5 * (a + b) / voxel_size_m * double(1 << kFracBits))));
    for (int e = 0; e < rows; ++e) {
      const double solid_angle = column_rad * (std::sin(bottom_rad + (e + 1) * row_rad) -
                                               std::sin(bottom_rad + e * row_rad));
      const double v = solid_angle * (b * b * b - a * a * a) / 3.0;
      volume[static_cast<std::size_t>(e) * rays.steps + k] = v;
      largest = std::max(largest, v);
    }
  }
  rays.unit_m3 = largest / kUnitsOfLargestStep;
  rays.weight.reserve(volume.size());
  for (double v : volume) {
    rays.weight.push_back(static_cast<std::uint32_t>(std::llround(v / rays.unit_m3)));
  }
  return rays;
}

FixedPosition fixedPosition(const Eigen::Vector3f& p_W, float voxel_size_m) {
  FixedPosition out;
  for (int a = 0; a < 3; ++a) {
    const double g = double(p_W[a]) / voxel_size_m;
    if (!std::isfinite(g) || std::abs(g) > kMaxVoxelCoord) {
      std::ostringstream message;
      message << "view gain: position (" << p_W.transpose()
              << ") is not finite or lies too far from the origin (limit "
              << kMaxVoxelCoord * voxel_size_m << " m)";
      throw InputError(message.str());
    }
    const std::int64_t q = std::llround(g * double(1 << kFracBits));
    const std::int64_t voxel = q >> kFracBits;  // floor
    out.voxel[a] = static_cast<int>(voxel);
    out.frac[a] = static_cast<int>(q - voxel * (std::int64_t{1} << kFracBits));
  }
  return out;
}

BlockBox fanBlocks(const FixedPosition& origin, const ViewGainRays& rays) {
  std::int32_t t_max = 0;
  for (std::int32_t t : rays.t_q) t_max = std::max(t_max, t);
  Eigen::Vector3i dir_max = Eigen::Vector3i::Zero();
  for (const Eigen::Vector4i& d : rays.dir_q) dir_max = dir_max.cwiseMax(d.head<3>().cwiseAbs());
  BlockBox box;
  for (int a = 0; a < 3; ++a) {
    // |offset| <= reach in 1/256 voxel; the fraction adds less than one voxel.
    const std::int32_t reach = ((dir_max[a] * t_max) >> kDirBits) + 1;
    const int lo = origin.voxel[a] + ((origin.frac[a] - reach) >> kFracBits);
    const int hi = origin.voxel[a] + ((origin.frac[a] + reach) >> kFracBits);
    box.lo[a] = lo >> 3;  // floor division by the block edge
    box.hi[a] = hi >> 3;
  }
  return box;
}

ViewGain finishViewGain(const std::uint64_t* bin_units, const ViewGainRays& rays,
                        const ViewGainConfig& config) {
  ViewGain gain;
  gain.bin_gain_m3.resize(config.yaw_bins);
  for (int b = 0; b < config.yaw_bins; ++b) {
    gain.bin_gain_m3[b] = static_cast<float>(double(bin_units[b]) * rays.unit_m3);
  }
  // The window's gain is piecewise linear in yaw, with corners where an edge of the window meets
  // an edge of a bin: its maximum lies on one of those yaws.
  const double bin_rad = kTwoPi / config.yaw_bins;
  const double half_window = 0.5 * std::min<double>(config.horizontal_fov_rad, kTwoPi);
  gain.best_gain_m3 = -1.0f;
  for (int b = 0; b < config.yaw_bins; ++b) {
    for (double side : {half_window, -half_window}) {
      double yaw = std::fmod(b * bin_rad + side, kTwoPi);
      if (yaw < 0.0) yaw += kTwoPi;
      const float g = gainAtYaw(gain, config, static_cast<float>(yaw));
      if (g > gain.best_gain_m3) {
        gain.best_gain_m3 = g;
        gain.best_yaw_rad = static_cast<float>(yaw);
      }
    }
  }
  if (gain.best_yaw_rad >= float(kTwoPi)) gain.best_yaw_rad = 0.0f;
  return gain;
}

}  // namespace strata::explore::internal
