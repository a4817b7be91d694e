#include <cmath>

#include "strata/raycast/raycast.h"
#include "strata/raycast/tsdf_sampling.h"

namespace strata {
namespace {

struct MarchContext {
  const TsdfMap& map;
  float voxel_size_m;
  float block_size_m;
  float min_weight;
  std::uint32_t max_steps;
};

float blockExitDistance(const Eigen::Vector3f& p_W, const Eigen::Vector3f& dir_W,
                        float block_size_m) {
  const Eigen::Vector3f lo = (p_W / block_size_m).array().floor() * block_size_m;
  const Eigen::Vector3f hi = lo.array() + block_size_m;
  float exit_t = INFINITY;
  for (int a = 0; a < 3; ++a) {
    const float inv = 1.0f / std::max(std::abs(dir_W[a]), 1e-12f);
    const float t = dir_W[a] > 0.0f ? (hi[a] - p_W[a]) * inv : (lo[a] - p_W[a]) * -inv;
    exit_t = std::min(exit_t, t);
  }
  return exit_t;
}

bool blockAllocatedAt(const MarchContext& c, const Eigen::Vector3f& p_W) {
  const BlockIndex b = (p_W / c.block_size_m).array().floor().cast<int>();
  return c.map.findBlock(b) != nullptr;
}

/// Same march as shaders/common/raycast_march.glsl.
bool marchRay(const MarchContext& c, const Eigen::Vector3f& origin_W, const Eigen::Vector3f& dir_W,
              float t_min, float t_max, float* t_hit) {
  float t = t_min;
  float previous_t = 0.0f;
  float previous_tsdf = 0.0f;
  bool previous_valid = false;
  for (std::uint32_t s = 0; s < c.max_steps && t <= t_max; ++s) {
    const Eigen::Vector3f p_W = origin_W + dir_W * t;
    float tsdf_m = 0.0f;
    if (!sampleTsdf(c.map, p_W, c.min_weight, &tsdf_m)) {
      previous_valid = false;
      t += blockAllocatedAt(c, p_W) ? c.voxel_size_m
                                    : blockExitDistance(p_W, dir_W, c.block_size_m) + 1e-4f;
      continue;
    }
    if (previous_valid && previous_tsdf > 0.0f && tsdf_m <= 0.0f) {
      *t_hit = previous_t + (t - previous_t) * previous_tsdf / (previous_tsdf - tsdf_m);
      return true;
    }
    previous_valid = true;
    previous_tsdf = tsdf_m;
    previous_t = t;
    t += std::max(c.voxel_size_m, 0.8f * tsdf_m);
  }
  return false;
}

Eigen::Vector3f surfaceNormal(const MarchContext& c, const Eigen::Vector3f& p_W) {
  float s[6];
  for (int i = 0; i < 6; ++i) {
    Eigen::Vector3f offset = Eigen::Vector3f::Zero();
    offset[i >> 1] = (i & 1) == 0 ? c.voxel_size_m : -c.voxel_size_m;
    if (!sampleTsdf(c.map, p_W + offset, c.min_weight, &s[i])) return Eigen::Vector3f::Zero();
  }
  const Eigen::Vector3f gradient(s[0] - s[1], s[2] - s[3], s[4] - s[5]);
  const float length = gradient.norm();
  return length > 0.0f ? Eigen::Vector3f(gradient / length) : Eigen::Vector3f::Zero();
}

}  // namespace

bool raycastRayReference(const TsdfMap& map, const Eigen::Vector3f& origin_W,
                         const Eigen::Vector3f& dir_W, float t_min, float t_max,
                         const RaycastOptions& options, float* t_hit) {
  const MapConfig& config = map.config();
  const MarchContext c{map, config.voxel_size_m, config.blockSize(), options.min_weight,
                       options.max_steps};
  return marchRay(c, origin_W, dir_W, t_min, t_max, t_hit);
}

RaycastImage raycastReference(const TsdfMap& map, const CameraIntrinsics& intrinsics,
                              const Eigen::Isometry3d& T_W_C, const RaycastOptions& options) {
  intrinsics.validate();
  const MapConfig& config = map.config();
  const FrameCamera camera = FrameCamera::from(intrinsics, T_W_C);
  const MarchContext c{map, config.voxel_size_m, config.blockSize(), options.min_weight,
                       options.max_steps};
  const int w = intrinsics.width_px;
  const int h = intrinsics.height_px;
  RaycastImage out{DepthImage(w, h), std::vector<Eigen::Vector3f>(static_cast<size_t>(w) * h,
                                                                  Eigen::Vector3f::Zero()),
                   ColorImage(w, h), std::vector<std::uint8_t>(static_cast<size_t>(w) * h, 0)};
  const Eigen::Matrix3f R_W_C = camera.T_W_C.topLeftCorner<3, 3>();
  const Eigen::Vector3f origin_W = camera.T_W_C.topRightCorner<3, 1>();
  for (int v = 0; v < h; ++v) {
    for (int u = 0; u < w; ++u) {
      const Eigen::Vector3f ray_C = pixelRay(static_cast<float>(u), static_cast<float>(v), camera.K);
      const float ray_scale = ray_C.norm();
      const Eigen::Vector3f dir_W = R_W_C * (ray_C / ray_scale);
      float t_hit = 0.0f;
      if (!marchRay(c, origin_W, dir_W, config.min_depth_m * ray_scale,
                    config.max_depth_m * ray_scale, &t_hit)) {
        continue;
      }
      const std::size_t index = static_cast<std::size_t>(v) * w + u;
      out.depth.depth_m[index] = t_hit / ray_scale;
      out.hit[index] = 1;
      const Eigen::Vector3f p_W = origin_W + dir_W * t_hit;
      out.normal_W[index] = surfaceNormal(c, p_W);
      const GlobalVoxelIndex nearest = (p_W / config.voxel_size_m).array().floor().cast<int>();
      if (const TsdfVoxel* voxel = observedVoxel(map, nearest, options.min_weight)) {
        out.color.rgb[index * 3 + 0] = voxel->color_rgba & 255u;
        out.color.rgb[index * 3 + 1] = (voxel->color_rgba >> 8) & 255u;
        out.color.rgb[index * 3 + 2] = (voxel->color_rgba >> 16) & 255u;
      }
    }
  }
  return out;
}

}  // namespace strata
