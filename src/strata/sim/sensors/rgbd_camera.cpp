#include "strata/sim/sensors/rgbd_camera.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <utility>
#include <vector>

#include "strata/core/error.h"
#include "strata/core/parallel_for.h"

namespace strata::sim {
namespace {

constexpr std::uint64_t kDepthNoiseStream = 0x64657074;  // "dept": rows of depth noise

// Depth of the 4-neighbour farthest from z (if the jump exceeds min_jump), else 0.
float depthAcrossEdge(const DepthImage& depth, int u, int v, double min_jump_m) {
  const float z = depth.at(u, v);
  const int du[4] = {-1, 1, 0, 0};
  const int dv[4] = {0, 0, -1, 1};
  float best = 0.0f;
  double best_jump = min_jump_m;
  for (int k = 0; k < 4; ++k) {
    const int nu = u + du[k], nv = v + dv[k];
    if (nu < 0 || nv < 0 || nu >= depth.width_px || nv >= depth.height_px) continue;
    const float other = depth.at(nu, nv);
    if (other <= 0.0f || std::abs(other - z) <= best_jump) continue;
    best_jump = std::abs(other - z);
    best = other;
  }
  return best;
}

// Ground truth per pixel: exact depth, shaded colour, object id.
void fillTruthRows(const PixelRayTable& table, const std::vector<Ray>& rays,
                   const std::vector<RayHit>& hits, const Lighting& lighting,
                   const std::optional<WorldTextureConfig>& texture, int begin, int end,
                   SimulatedFrame& out) {
  const int width = out.depth_true.width_px;
  for (std::size_t i = static_cast<std::size_t>(begin) * width;
       i < static_cast<std::size_t>(end) * width; ++i) {
    const RayHit& hit = hits[i];
    if (!hit.hit()) continue;
    out.depth_true.depth_m[i] = hit.t_m * table.z_per_t[i];  // z = t * d_C.z
    out.object_ids.ids[i] = hit.object_id;
    std::array<std::uint8_t, 3> albedo = hit.material.albedo;
    if (texture) {
      const Eigen::Vector3d p_W = (rays[i].origin_W + hit.t_m * rays[i].direction_W).cast<double>();
      const double factor = worldTexture(*texture, p_W);  // in [1 - contrast, 1]
      for (std::uint8_t& channel : albedo)
        channel = static_cast<std::uint8_t>(std::lround(channel * factor));
    }
    const std::array<std::uint8_t, 3> rgb = shade(albedo, lighting, hit.normal_W.cast<double>());
    std::copy(rgb.begin(), rgb.end(), out.color.rgb.begin() + 3 * i);
  }
}

// Measured depth of one row: noise model, range limits, quantisation. One random stream per row.
void measureRow(const RgbdCameraConfig& config, const std::vector<Ray>& rays,
                const std::vector<RayHit>& hits, std::uint64_t frame_seed, int v,
                SimulatedFrame& out) {
  const int width = out.depth.width_px;
  Rng rng = Rng::stream(frame_seed, kDepthNoiseStream, static_cast<std::uint64_t>(v));
  for (int u = 0; u < width; ++u) {
    const DepthPixelDraws draws = DepthPixelDraws::draw(rng);  // drawn for every pixel
    const std::size_t i = static_cast<std::size_t>(v) * width + u;
    const RayHit& hit = hits[i];
    if (!hit.hit()) continue;
    DepthPixel pixel;
    pixel.z_true_m = out.depth_true.depth_m[i];
    pixel.cos_incidence = std::abs(hit.normal_W.dot(rays[i].direction_W));
    pixel.albedo_luminance = static_cast<float>(luminance(hit.material.albedo));
    pixel.reflectivity = hit.material.reflectivity;
    pixel.z_across_edge_m = depthAcrossEdge(out.depth_true, u, v, config.noise.flying_min_jump_m);
    float z = applyDepthNoise(config.noise, pixel, draws);
    if (z < config.min_range_m || z > config.max_range_m) z = 0.0f;
    if (config.noise.quantize) z = quantizeDepth(z, config.depth_scale);
    out.depth.depth_m[i] = z;
  }
}

RgbdCameraConfig validated(RgbdCameraConfig config) {
  config.validate();
  return config;
}

}  // namespace

void RgbdCameraConfig::validate() const {
  intrinsics.validate();
  if (!(min_range_m >= 0.0 && min_range_m < max_range_m) || !std::isfinite(max_range_m)) {
    throw InputError("RgbdCameraConfig: min_range_m/max_range_m need 0 <= min < max, finite");
  }
  if (!(depth_scale > 0.0) || !std::isfinite(depth_scale)) {
    throw InputError("RgbdCameraConfig: depth_scale must be positive and finite");
  }
  if (threads < 0) throw InputError("RgbdCameraConfig: threads must be >= 0 (0 = all cores)");
  noise.validate();
  if (color_texture) color_texture->validate();
}

RgbdCamera::RgbdCamera(RgbdCameraConfig config)
    : config_(validated(std::move(config))), ray_table_(makePixelRayTable(config_.intrinsics)) {}

SimulatedFrame RgbdCamera::render(const RayScene& scene, const Eigen::Isometry3d& T_W_C,
                                  const Lighting& lighting, std::uint64_t frame_seed) const {
  validatePose(T_W_C, "RgbdCamera::render pose");
  lighting.validate();
  const int width = config_.intrinsics.width_px;
  const int height = config_.intrinsics.height_px;
  const std::vector<Ray> rays =
      worldRays(ray_table_, T_W_C, std::numeric_limits<float>::infinity(), config_.threads);
  std::vector<RayHit> hits;
  scene.intersect(rays, hits);  // one batch: the scene packs and parallelises it

  SimulatedFrame out{DepthImage(width, height), DepthImage(width, height),
                     ColorImage(width, height), ObjectIdImage(width, height)};
  parallelForBlocks(height, config_.threads, [&](int begin, int end) {
    fillTruthRows(ray_table_, rays, hits, lighting, config_.color_texture, begin, end, out);
  });
  // Second pass: flying pixels read neighbouring rows of depth_true.
  parallelForBlocks(height, config_.threads, [&](int begin, int end) {
    for (int v = begin; v < end; ++v) measureRow(config_, rays, hits, frame_seed, v, out);
  });
  return out;
}

RgbdFrame makeRgbdFrame(SimulatedFrame frame, const Eigen::Isometry3d& T_W_C, double timestamp_s,
                        std::string name) {
  RgbdFrame out;
  out.timestamp_s = timestamp_s;
  out.name = std::move(name);
  out.depth = std::move(frame.depth);
  out.color = std::move(frame.color);
  out.T_W_C = T_W_C;
  return out;
}

}  // namespace strata::sim
