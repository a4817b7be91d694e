#pragma once
// Information gain of candidate viewpoints for exploration: how much unknown volume a camera at a
// position would see, per heading, so that a planner picks the best yaw for each sampled position
// instead of sampling yaw (Publication V of docs/plan.md).
//
// Model. Around each position, rays fan out over the full circle in `yaw_bins` columns (each
// column `rays_per_bin` rays across it) and over the camera's vertical field of view in
// `elevation_rays` rows. Each ray is marched through the TSDF every `step_voxels` voxels from
// `min_range_m` to `max_range_m`; it stops at the first observed voxel that is occupied (observed
// with tsdf <= 0, or a surface voxel: |tsdf| < half a voxel); each step that lands in an unknown
// voxel (block not allocated, or weight < min_weight) adds the volume the ray stands for there
// (its solid angle x distance^2 x step). A bin's gain is the sum over its rays (m^3); the gain of
// a yaw is the sum over the bins the horizontal field of view covers centred on it; best_yaw is
// the centre of the best window. Device: shaders/explore/view_gain.comp; reference:
// viewGainReference, the same march on the host map; tests hold them to each other.
// Frames: world (z up); yaw counter-clockwise about +z from +x, radians.
// Thread safety: ViewGainKernel is not thread safe; the reference is.
#include <Eigen/Core>
#include <cstdint>
#include <memory>
#include <vector>

#include "map/tsdf_map.h"
#include "vk/vk.h"

namespace strata {
class DeviceTsdfMap;
}

namespace strata::explore {

struct ViewGainConfig {
  float min_range_m = 0.3f;
  float max_range_m = 4.0f;
  float horizontal_fov_rad = 1.0472f;  // 60 degrees
  float vertical_fov_rad = 0.8203f;    // 47 degrees
  int yaw_bins = 72;                   // 5 degree columns over the full circle
  int rays_per_bin = 2;
  int elevation_rays = 16;
  float step_voxels = 1.0f;
  float min_weight = 1e-3f;
  int tsdf_layer = 0;  // device kernel only

  /// Throws InputError naming the bad field.
  void validate() const;
};

struct ViewGain {
  float best_yaw_rad = 0.0f;
  float best_gain_m3 = 0.0f;           // gain of best_yaw's window
  std::vector<float> bin_gain_m3;      // per yaw bin (bin b centred on (b + 0.5) * 2 pi / bins)
};

/// Host reference: the gain at every position on the host map.
std::vector<ViewGain> viewGainReference(const TsdfMap& map, const ViewGainConfig& config,
                                        const std::vector<Eigen::Vector3f>& positions_W);

/// The gain of a given yaw from the bins (the window the field of view covers centred on it).
float gainAtYaw(const ViewGain& gain, const ViewGainConfig& config, float yaw_rad);

/// Device kernel: every position of the batch in one dispatch.
class ViewGainKernel {
 public:
  ViewGainKernel(vk::Context& context, const ViewGainConfig& config);
  std::vector<ViewGain> run(DeviceTsdfMap& map, const std::vector<Eigen::Vector3f>& positions_W,
                            double* device_ms = nullptr);
  const ViewGainConfig& config() const { return config_; }

 private:
  struct Impl;
  std::shared_ptr<Impl> impl_;
  ViewGainConfig config_;
};

}  // namespace strata::explore
