#include "strata/sim/sensors/grey_camera.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

#include "strata/core/error.h"
#include "strata/core/parallel_for.h"
#include "strata/sim/rng.h"

namespace strata::sim {
namespace {

constexpr std::uint64_t kGreyNoiseStream = 0x67726579;  // "grey": rows of pixel noise
constexpr std::uint64_t kExposureStream = 0x6578706f;   // "expo": a frame's gain and offset

// Grey level of one hit: luminance(albedo) x texture x Lambert factor x 255.
double greyLevel(const GreyCameraConfig& config, const Lighting& lighting, const Ray& ray,
                 const RayHit& hit) {
  const Eigen::Vector3d p_W = (ray.origin_W + hit.t_m * ray.direction_W).cast<double>();
  return 255.0 * luminance(hit.material.albedo) * worldTexture(config.texture, p_W) *
         shadingFactor(lighting, hit.normal_W.cast<double>());
}

GreyCameraConfig validated(GreyCameraConfig config) {
  config.validate();
  return config;
}

}  // namespace

void GreyCameraConfig::validate() const {
  intrinsics.validate();
  if (!(baseline_m >= 0.0) || !std::isfinite(baseline_m)) {
    throw InputError("GreyCameraConfig: baseline_m must be finite and >= 0 (0 = mono)");
  }
  if (!(pixel_noise_sigma >= 0.0) || !std::isfinite(pixel_noise_sigma)) {
    throw InputError("GreyCameraConfig: pixel_noise_sigma must be finite and >= 0");
  }
  if (!(exposure_gain_sigma >= 0.0 && exposure_gain_sigma < 0.5) ||
      !(exposure_offset_sigma >= 0.0) || !std::isfinite(exposure_offset_sigma)) {
    throw InputError("GreyCameraConfig: exposure_gain_sigma must be in [0, 0.5) and "
                     "exposure_offset_sigma finite and >= 0");
  }
  if (threads < 0) throw InputError("GreyCameraConfig: threads must be >= 0 (0 = all cores)");
  texture.validate();
}

GreyCamera::GreyCamera(GreyCameraConfig config)
    : config_(validated(std::move(config))), ray_table_(makePixelRayTable(config_.intrinsics)) {}

GreyFrame GreyCamera::render(const RayScene& scene, const Eigen::Isometry3d& T_W_C,
                             const Lighting& lighting, std::uint64_t frame_seed) const {
  validatePose(T_W_C, "GreyCamera::render pose");
  lighting.validate();
  GreyFrame frame;
  frame.T_W_eye.push_back(T_W_C);
  if (config_.baseline_m > 0.0) {
    frame.T_W_eye.push_back(T_W_C * Eigen::Translation3d(config_.baseline_m, 0.0, 0.0));
  }
  if (config_.exposure_gain_sigma > 0.0 || config_.exposure_offset_sigma > 0.0) {
    Rng rng = Rng::stream(frame_seed, kExposureStream, 0);
    // NOTE: clamped at 3 sigma so a rare draw never inverts or blacks out a frame.
    frame.exposure_gain = 1.0 + config_.exposure_gain_sigma * std::clamp(rng.normal(), -3.0, 3.0);
    frame.exposure_offset = config_.exposure_offset_sigma * std::clamp(rng.normal(), -3.0, 3.0);
  }
  for (std::size_t eye = 0; eye < frame.T_W_eye.size(); ++eye) {
    frame.eyes.push_back(renderEye(scene, frame.T_W_eye[eye], lighting,
                                   hashCombine(frame_seed, eye), frame.exposure_gain,
                                   frame.exposure_offset));
  }
  return frame;
}

GreyImage GreyCamera::renderEye(const RayScene& scene, const Eigen::Isometry3d& T_W_eye,
                                const Lighting& lighting, std::uint64_t eye_seed, double gain,
                                double offset) const {
  const int width = config_.intrinsics.width_px;
  const int height = config_.intrinsics.height_px;
  const std::vector<Ray> rays =
      worldRays(ray_table_, T_W_eye, std::numeric_limits<float>::infinity(), config_.threads);
  std::vector<RayHit> hits;
  scene.intersect(rays, hits);
  GreyImage image(width, height);
  parallelForBlocks(height, config_.threads, [&](int begin, int end) {
    for (int v = begin; v < end; ++v) {
      Rng rng = Rng::stream(eye_seed, kGreyNoiseStream, static_cast<std::uint64_t>(v));
      for (int u = 0; u < width; ++u) {
        const std::size_t i = static_cast<std::size_t>(v) * width + u;
        const double noise = config_.pixel_noise_sigma * rng.normal();  // drawn for every pixel
        if (!hits[i].hit()) continue;
        const double level =
            gain * greyLevel(config_, lighting, rays[i], hits[i]) + offset + noise;
        image.pixels[i] = static_cast<std::uint8_t>(std::clamp(level, 0.0, 255.0) + 0.5);
      }
    }
  });
  return image;
}

}  // namespace strata::sim
