#pragma once
// Simulated grey (luminance) camera, mono or stereo, for visual(-inertial) odometry: the RGB-D
// camera's Lambert shading times a world-anchored procedural texture, plus Gaussian pixel noise.
#include <Eigen/Geometry>
#include <cstdint>
#include <vector>

#include "strata/core/types.h"
#include "strata/sim/ray_scene.h"
#include "strata/sim/sensors/lighting.h"
#include "strata/sim/sensors/pinhole_rays.h"
#include "strata/sim/sensors/sensor_images.h"
#include "strata/sim/sensors/world_texture.h"

namespace strata::sim {

struct GreyCameraConfig {
  CameraIntrinsics intrinsics;  // both eyes
  /// 0 = mono. > 0 = stereo: the right eye sits baseline_m along the left eye's +x axis, same
  /// orientation (rectified pair). EuRoC's MT9V034 pair has about 0.11 m.
  double baseline_m = 0.0;
  WorldTextureConfig texture;
  /// Gaussian read noise, grey levels (0 = noise-free).
  double pixel_noise_sigma = 1.0;
  /// Per-frame exposure change (auto-exposure, flicker): each frame draws gain = 1 + sigma_g n1
  /// and offset = sigma_o n2 (n Gaussian, seeded by the frame seed, shared by both eyes of a pair
  /// as with synchronised exposure) and every level becomes gain * level + offset before the
  /// read noise. Defaults 0: constant exposure.
  double exposure_gain_sigma = 0.0;    // relative
  double exposure_offset_sigma = 0.0;  // grey levels
  /// Threads for shading (0 = hardware concurrency); the output never depends on it.
  int threads = 0;

  /// Throws InputError naming the first bad field.
  void validate() const;
};

struct GreyFrame {
  std::vector<GreyImage> eyes;             // [left] or [left, right]
  std::vector<Eigen::Isometry3d> T_W_eye;  // camera-to-world pose of each eye
  double exposure_gain = 1.0;              // the frame's drawn exposure (truth)
  double exposure_offset = 0.0;
};

/// Thread safety: render() may be called from several threads at once.
class GreyCamera {
 public:
  explicit GreyCamera(GreyCameraConfig config);

  /// Renders each eye; T_W_C is the left (or only) eye. Same seed, same bytes.
  GreyFrame render(const RayScene& scene, const Eigen::Isometry3d& T_W_C, const Lighting& lighting,
                   std::uint64_t frame_seed) const;

  const GreyCameraConfig& config() const { return config_; }

 private:
  GreyImage renderEye(const RayScene& scene, const Eigen::Isometry3d& T_W_eye,
                      const Lighting& lighting, std::uint64_t eye_seed, double gain,
                      double offset) const;

  GreyCameraConfig config_;
  PixelRayTable ray_table_;
};

}  // namespace strata::sim
