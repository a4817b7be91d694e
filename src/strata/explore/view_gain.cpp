#include "strata/explore/view_gain.h"

#include <cmath>
#include <sstream>
#include <string>

#include "strata/core/error.h"

namespace strata::explore {
namespace {

constexpr double kTwoPi = 2.0 * M_PI;
constexpr int kMaxYawBins = 4096;
constexpr int kMaxRaysPerPosition = 1 << 20;

void require(bool ok, const std::string& field, const std::string& what) {
  if (!ok) throw InputError("ViewGainConfig." + field + ": " + what);
}

}  // namespace

void ViewGainConfig::validate() const {
  require(std::isfinite(min_range_m) && min_range_m >= 0.0f, "min_range_m",
          "must be finite and >= 0");
  require(std::isfinite(max_range_m) && max_range_m > min_range_m, "max_range_m",
          "must be finite and greater than min_range_m");
  require(horizontal_fov_rad > 0.0f && horizontal_fov_rad <= float(kTwoPi), "horizontal_fov_rad",
          "must be in (0, 2 pi]");
  require(vertical_fov_rad > 0.0f && vertical_fov_rad < float(M_PI), "vertical_fov_rad",
          "must be in (0, pi)");
  require(yaw_bins >= 1 && yaw_bins <= kMaxYawBins, "yaw_bins", "must be in [1, 4096]");
  require(rays_per_bin >= 1, "rays_per_bin", "must be >= 1");
  require(elevation_rays >= 1, "elevation_rays", "must be >= 1");
  require(double(yaw_bins) * rays_per_bin * elevation_rays <= kMaxRaysPerPosition, "rays_per_bin",
          "yaw_bins x rays_per_bin x elevation_rays must be at most 2^20 rays per position");
  require(std::isfinite(step_voxels) && step_voxels >= 0.1f, "step_voxels",
          "must be finite and >= 0.1");
  require(std::isfinite(min_weight) && min_weight > 0.0f, "min_weight", "must be finite and > 0");
  require(tsdf_layer >= 0, "tsdf_layer", "must be >= 0");
}

float gainAtYaw(const ViewGain& gain, const ViewGainConfig& config, float yaw_rad) {
  const int bins = config.yaw_bins;
  if (static_cast<int>(gain.bin_gain_m3.size()) != bins) {
    std::ostringstream message;
    message << "gainAtYaw: the gain has " << gain.bin_gain_m3.size() << " bins, the config "
            << bins;
    throw InputError(message.str());
  }
  if (!std::isfinite(yaw_rad)) throw InputError("gainAtYaw: the yaw is not finite");
  // Window [yaw - h/2, yaw + h/2] in bin units, its start brought into [0, bins).
  const double bin_rad = kTwoPi / bins;
  const double width = std::min<double>(config.horizontal_fov_rad, kTwoPi) / bin_rad;
  double lo = (double(yaw_rad) / bin_rad) - 0.5 * width;
  lo -= std::floor(lo / bins) * bins;
  const double hi = lo + width;
  double sum = 0.0;
  for (int i = static_cast<int>(std::floor(lo)); i < hi; ++i) {
    const double overlap = std::min(hi, i + 1.0) - std::max(lo, double(i));
    if (overlap > 0.0) sum += overlap * gain.bin_gain_m3[((i % bins) + bins) % bins];
  }
  return static_cast<float>(sum);
}

}  // namespace strata::explore
