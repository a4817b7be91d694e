// TEMPORARY stand-in for engine/explore/view_gain.cpp and its device kernel, so exploration runs
// before they land: the same contract (engine/explore/view_gain.h), all on the host.
// ViewGainKernel::run downloads the device map and runs the reference. Delete this file (and its
// line in host/explore/CMakeLists.txt) once the real implementation is merged.
#include <algorithm>
#include <cmath>

#include "core/error.h"
#include "explore/view_gain.h"
#include "map/device_tsdf_map.h"

namespace strata::explore {
namespace {

constexpr float kTwoPi = 6.28318530718f;

float binWidth(const ViewGainConfig& c) { return kTwoPi / static_cast<float>(c.yaw_bins); }

/// Unknown volume along one ray (m^3 per steradian of the ray's solid angle).
float marchRay(const TsdfMap& map, const ViewGainConfig& c, const Eigen::Vector3f& origin,
               const Eigen::Vector3f& direction) {
  const float voxel = map.config().voxel_size_m;
  const float step = c.step_voxels * voxel;
  float sum = 0.0f;
  for (float s = c.min_range_m; s <= c.max_range_m; s += step) {
    const Eigen::Vector3f p = origin + s * direction;
    const GlobalVoxelIndex v = (p / voxel).array().floor().cast<int>();
    const TsdfVoxel* voxel_ptr = map.findVoxel(v);
    if (voxel_ptr == nullptr || voxel_ptr->weight < c.min_weight) {
      sum += s * s * step;
      continue;
    }
    if (voxel_ptr->tsdf_m <= 0.0f || std::abs(voxel_ptr->tsdf_m) < 0.5f * voxel) break;
  }
  return sum;
}

ViewGain gainAt(const TsdfMap& map, const ViewGainConfig& c, const Eigen::Vector3f& p) {
  ViewGain out;
  out.bin_gain_m3.assign(static_cast<std::size_t>(c.yaw_bins), 0.0f);
  const float d_yaw = binWidth(c) / static_cast<float>(c.rays_per_bin);
  const float d_elev = c.vertical_fov_rad / static_cast<float>(c.elevation_rays);
  for (int b = 0; b < c.yaw_bins; ++b) {
    for (int r = 0; r < c.rays_per_bin; ++r) {
      const float yaw = (static_cast<float>(b) + (r + 0.5f) / c.rays_per_bin) * binWidth(c);
      for (int e = 0; e < c.elevation_rays; ++e) {
        const float elev = -0.5f * c.vertical_fov_rad + (e + 0.5f) * d_elev;
        const Eigen::Vector3f dir(std::cos(elev) * std::cos(yaw), std::cos(elev) * std::sin(yaw),
                                  std::sin(elev));
        const float solid_angle = d_yaw * d_elev * std::cos(elev);
        out.bin_gain_m3[b] += solid_angle * marchRay(map, c, p, dir);
      }
    }
  }
  // Candidate headings: bin centres and bin edges.
  for (int k = 0; k < 2 * c.yaw_bins; ++k) {
    const float yaw = 0.5f * static_cast<float>(k) * binWidth(c);
    const float g = gainAtYaw(out, c, yaw);
    if (g > out.best_gain_m3) {
      out.best_gain_m3 = g;
      out.best_yaw_rad = yaw;
    }
  }
  if (out.best_yaw_rad > 3.14159265f) out.best_yaw_rad -= kTwoPi;
  return out;
}

}  // namespace

void ViewGainConfig::validate() const {
  if (!(min_range_m >= 0.0f) || !(max_range_m > min_range_m) || !std::isfinite(max_range_m)) {
    throw InputError("view gain ranges: need 0 <= min_range_m < max_range_m");
  }
  if (!(horizontal_fov_rad > 0.0f && horizontal_fov_rad <= kTwoPi)) {
    throw InputError("view gain horizontal_fov_rad must be in (0, 2 pi]");
  }
  if (!(vertical_fov_rad > 0.0f && vertical_fov_rad < 3.14159265f)) {
    throw InputError("view gain vertical_fov_rad must be in (0, pi)");
  }
  if (yaw_bins < 1 || rays_per_bin < 1 || elevation_rays < 1) {
    throw InputError("view gain yaw_bins, rays_per_bin, elevation_rays must be >= 1");
  }
  if (!(step_voxels > 0.0f)) throw InputError("view gain step_voxels must be > 0");
  if (!(min_weight >= 0.0f)) throw InputError("view gain min_weight must be >= 0");
}

float gainAtYaw(const ViewGain& gain, const ViewGainConfig& config, float yaw_rad) {
  const float width = binWidth(config);
  float sum = 0.0f;
  for (int b = 0; b < static_cast<int>(gain.bin_gain_m3.size()); ++b) {
    const float centre = (static_cast<float>(b) + 0.5f) * width;
    float diff = std::fmod(std::abs(centre - yaw_rad), kTwoPi);
    diff = std::min(diff, kTwoPi - diff);
    if (diff <= 0.5f * config.horizontal_fov_rad + 1e-5f) sum += gain.bin_gain_m3[b];
  }
  return sum;
}

std::vector<ViewGain> viewGainReference(const TsdfMap& map, const ViewGainConfig& config,
                                        const std::vector<Eigen::Vector3f>& positions_W) {
  config.validate();
  std::vector<ViewGain> out;
  out.reserve(positions_W.size());
  for (const Eigen::Vector3f& p : positions_W) out.push_back(gainAt(map, config, p));
  return out;
}

struct ViewGainKernel::Impl {
  vk::Context* context = nullptr;
};

ViewGainKernel::ViewGainKernel(vk::Context& context, const ViewGainConfig& config)
    : impl_(std::make_shared<Impl>()), config_(config) {
  config_.validate();
  impl_->context = &context;
}

std::vector<ViewGain> ViewGainKernel::run(DeviceTsdfMap& map,
                                          const std::vector<Eigen::Vector3f>& positions_W,
                                          double* device_ms) {
  TsdfMap host(map.config());
  map.download(host, config_.tsdf_layer);
  if (device_ms != nullptr) *device_ms = 0.0;
  return viewGainReference(host, config_, positions_W);
}

}  // namespace strata::explore
