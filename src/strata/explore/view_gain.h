#pragma once
// Information gain of candidate viewpoints for exploration: how much unknown volume a camera at a
// position would see, per heading, so that a planner picks the best yaw for each sampled position
// instead of sampling yaw (Publication V of docs/plan.md).
//
// Model. Around each position, rays fan out over the full circle in `yaw_bins` columns (each
// column `rays_per_bin` rays across it) and over the camera's vertical field of view in
// `elevation_rays` rows (centred on the horizon). Each ray is cut into shells of
// step_voxels x voxel from `min_range_m` to `max_range_m` (the last one shorter) and sampled at
// each shell's middle; it stops at the first observed voxel that is occupied (weight >=
// min_weight and tsdf < half a voxel: inside, or a surface voxel); each sample that lands in an
// unknown voxel (block not allocated, or weight < min_weight) adds the volume of its shell
// segment (the ray's solid angle x (b^3 - a^3) / 3 for the shell [a, b]); observed free voxels
// add nothing. So on an empty map a bin gains exactly the volume of its sector of the fan.
// A bin's gain is the sum over its rays (m^3); the gain of a yaw is the integral of the bins over
// the horizontal field of view centred on it (bins partly inside count in proportion); best_yaw
// is the yaw of the best such window, in [0, 2 pi).
// Device: shaders/explore/view_gain.comp; reference: viewGainReference. Both march the same
// fixed-point rays and add the same integer volumes (units of ~1e-7 of a step's volume), so their
// results are equal, not merely close; tests hold them to each other.
// Frames: world (z up); yaw counter-clockwise about +z from +x, radians.
// Errors: InputError for a bad config (naming the field), a position that is not finite or lies
// beyond 4e6 voxels of the origin, or rays longer than 512 voxels (max_range_m / voxel size).
// Thread safety: ViewGainKernel is not thread safe; the reference and gainAtYaw are.
#include <Eigen/Core>
#include <cstdint>
#include <memory>
#include <vector>

#include "strata/map/tsdf_map.h"
#include "strata/vk/vk.h"

namespace strata {
class DeviceTsdfMap;
}

namespace strata::explore {

struct ViewGainConfig {
  float min_range_m = 0.3f;            // the camera's near limit: nothing nearer is seen
  float max_range_m = 4.0f;            // far limit; cost grows linearly with it
  float horizontal_fov_rad = 1.0472f;  // 60 degrees: the window of bins a yaw sees
  float vertical_fov_rad = 0.8203f;    // 47 degrees, centred on the horizon (< pi)
  int yaw_bins = 72;                   // 5 degree columns over the full circle
  int rays_per_bin = 2;                // more: finer sampling across a column, linear cost
  int elevation_rays = 16;             // rows over the vertical field of view
  float step_voxels = 1.0f;            // march step; > 1 is faster but may skip thin walls
  float min_weight = 1e-3f;            // a voxel is observed from this weight on (> 0)
  int tsdf_layer = 0;                  // device kernel only: which TSDF layer of the map

  /// Throws InputError naming the bad field.
  void validate() const;
};

struct ViewGain {
  float best_yaw_rad = 0.0f;       // in [0, 2 pi)
  float best_gain_m3 = 0.0f;       // gain of best_yaw's window
  std::vector<float> bin_gain_m3;  // per yaw bin (bin b centred on (b + 0.5) * 2 pi / bins)
};

/// Host reference: the gain at every position on the host map.
std::vector<ViewGain> viewGainReference(const TsdfMap& map, const ViewGainConfig& config,
                                        const std::vector<Eigen::Vector3f>& positions_W);

/// The gain of a given yaw from the bins (the window the field of view covers centred on it;
/// bins partly inside count in proportion). Any finite yaw; bins.size() must be config.yaw_bins.
float gainAtYaw(const ViewGain& gain, const ViewGainConfig& config, float yaw_rad);

/// Device kernel: a table of the map's blocks around the batch (one pass over the hash table),
/// then every position of the batch in one dispatch (one invocation per ray); batches spread so
/// wide that the table would exceed 4M blocks go in several such pairs.
class ViewGainKernel {
 public:
  /// Validates the config (InputError).
  ViewGainKernel(vk::Context& context, const ViewGainConfig& config);
  /// Host->device copies of the positions (and of the ray tables when the map's voxel size
  /// changes) and the device->host copy of the bins happen here. InputError for a tsdf_layer the
  /// map lacks; `device_ms` gets the dispatch's device time.
  std::vector<ViewGain> run(DeviceTsdfMap& map, const std::vector<Eigen::Vector3f>& positions_W,
                            double* device_ms = nullptr);
  const ViewGainConfig& config() const { return config_; }

 private:
  struct Impl;
  std::shared_ptr<Impl> impl_;
  ViewGainConfig config_;
};

}  // namespace strata::explore
