#pragma once
// Simulated pinhole RGB-D camera: renders depth, colour and object ids through any RayScene, with
// the structured-light noise model of depth_noise.h.
#include <Eigen/Geometry>
#include <cstdint>
#include <optional>
#include <string>

#include "strata/core/types.h"
#include "strata/sim/ray_scene.h"
#include "strata/sim/sensors/depth_noise.h"
#include "strata/sim/sensors/lighting.h"
#include "strata/sim/sensors/pinhole_rays.h"
#include "strata/sim/sensors/sensor_images.h"
#include "strata/sim/sensors/world_texture.h"

namespace strata::sim {

struct RgbdCameraConfig {
  CameraIntrinsics intrinsics;  // default 640x480, f = 525 px (TUM / Kinect v1)
  /// Measured depth outside [min, max] is reported as 0 (Kinect v1 works from about 0.4 to 5 m).
  double min_range_m = 0.3;
  double max_range_m = 5.0;
  /// Units per metre of the 16-bit depth format (TUM RGB-D: 5000, i.e. 0.2 mm, up to 13.1 m).
  double depth_scale = 5000.0;
  DepthNoiseConfig noise;
  /// When set, the colour's albedo is multiplied by this world-anchored texture, as the grey
  /// camera's is (sensors/grey_camera.h): surfaces then show corners for feature detectors, as
  /// real ones do. nullopt (the default): flat-shaded colour. Depth never depends on it.
  std::optional<WorldTextureConfig> color_texture;
  /// Threads for shading and noise (0 = hardware concurrency). Ray casting parallelism is the
  /// scene's own. The output never depends on this.
  int threads = 0;

  /// Throws InputError naming the first bad field.
  void validate() const;
};

struct SimulatedFrame {
  /// What the sensor reports: noise, dropouts, range limits and quantisation; 0 = no depth.
  DepthImage depth;
  /// Ground truth: exact camera-frame z of the first hit at every pixel that hit anything, no
  /// range limit, no noise, no quantisation; 0 where the ray hit nothing.
  DepthImage depth_true;
  /// Albedo (x the colour texture when configured) x Lambert shading of the first hit; black
  /// where the ray hit nothing.
  ColorImage color;
  /// Object id of the first hit (kNoHitObjectId = -1 where none), also where depth dropped out.
  ObjectIdImage object_ids;
};

/// Thread safety: render() may be called from several threads at once.
class RgbdCamera {
 public:
  /// Validates the config (InputError on a bad field).
  explicit RgbdCamera(RgbdCameraConfig config);

  /// Renders the view from camera-to-world pose T_W_C (optical axis +z, x right, y down). Pixel
  /// (u, v) looks through its centre at integer coordinates. `frame_seed` picks the noise: the same
  /// seed gives byte-identical images on any machine and thread count.
  SimulatedFrame render(const RayScene& scene, const Eigen::Isometry3d& T_W_C,
                        const Lighting& lighting, std::uint64_t frame_seed) const;

  const RgbdCameraConfig& config() const { return config_; }

 private:
  RgbdCameraConfig config_;
  PixelRayTable ray_table_;
};

/// An engine frame from a simulated one (measured depth and colour, the given pose).
RgbdFrame makeRgbdFrame(SimulatedFrame frame, const Eigen::Isometry3d& T_W_C, double timestamp_s,
                        std::string name);

}  // namespace strata::sim
