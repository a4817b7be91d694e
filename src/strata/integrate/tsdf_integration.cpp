#include "strata/integrate/tsdf_integration.h"

#include <algorithm>
#include <cmath>

#include "strata/core/parallel_for.h"
#include "strata/integrate/block_allocation.h"
#include "strata/integrate/normal_estimation.h"

namespace strata {
namespace {

std::uint32_t blendColor(std::uint32_t old_rgba, std::uint32_t new_rgba, float old_weight,
                         float weight) {
  std::uint32_t out = 0;
  for (int channel = 0; channel < 3; ++channel) {
    const float old_c = static_cast<float>((old_rgba >> (8 * channel)) & 255u);
    const float new_c = static_cast<float>((new_rgba >> (8 * channel)) & 255u);
    const float c = (old_c * old_weight + new_c * weight) / (old_weight + weight);
    const auto q = static_cast<std::uint32_t>(std::clamp(std::floor(c + 0.5f), 0.0f, 255.0f));
    out |= q << (8 * channel);
  }
  return out;
}

void integrateBlock(TsdfBlock& block, const BlockIndex& index, const RgbdFrame& frame,
                    const std::vector<Eigen::Vector4f>& normals_C, const FrameCamera& camera,
                    const MapConfig& config) {
  const ColorImage* color = frame.color.empty() ? nullptr : &frame.color;
  for (int z = 0; z < kBlockEdge; ++z) {
    for (int y = 0; y < kBlockEdge; ++y) {
      for (int x = 0; x < kBlockEdge; ++x) {
        const Eigen::Vector3f p_W =
            voxelCenter(index * kBlockEdge + Eigen::Vector3i(x, y, z), config.voxel_size_m);
        integrateVoxelReference(block[linearVoxelIndex(x, y, z)], p_W, frame.depth, &normals_C,
                                color, camera, config);
      }
    }
  }
}

}  // namespace

std::uint32_t packedPixelColor(const ColorImage& color, int u, int v) {
  if (color.empty()) return 0;
  const std::uint8_t* p = &color.rgb[(static_cast<std::size_t>(v) * color.width_px + u) * 3];
  return packRgb(p[0], p[1], p[2]);
}

VoxelObservation observeVoxelReference(const Eigen::Vector3f& p_W, const DepthImage& depth,
                                       const std::vector<Eigen::Vector4f>* normals_C,
                                       const FrameCamera& camera, const MapConfig& config) {
  VoxelObservation o;
  const Eigen::Vector3f p_C = (camera.T_C_W * p_W.homogeneous()).head<3>();
  if (p_C.z() <= 0.0f) return o;
  const float u = camera.K[0] * p_C.x() / p_C.z() + camera.K[2];
  const float v = camera.K[1] * p_C.y() / p_C.z() + camera.K[3];
  const float pixel_u = std::floor(u + 0.5f);
  const float pixel_v = std::floor(v + 0.5f);
  if (pixel_u < 0.0f || pixel_v < 0.0f || pixel_u >= static_cast<float>(depth.width_px) ||
      pixel_v >= static_cast<float>(depth.height_px)) {
    return o;
  }
  const int pu = static_cast<int>(pixel_u);
  const int pv = static_cast<int>(pixel_v);
  const float d = depth.at(pu, pv);
  if (!depthValid(d, config.min_depth_m, config.max_depth_m)) return o;

  const float truncation_m = config.truncationDistance();
  // The distance along the ray decides which voxels are updated (the band behind the surface),
  // whichever distance is stored.
  const float ray_sdf_m =
      (d - p_C.z()) * Eigen::Vector3f(p_C.x() / p_C.z(), p_C.y() / p_C.z(), 1.0f).norm();
  o.ray_sdf_m = ray_sdf_m;
  o.u_px = pu;
  o.v_px = pv;
  if (ray_sdf_m < -truncation_m) return o;
  float sdf_m = ray_sdf_m;
  const Eigen::Vector4f normal =
      normals_C != nullptr ? (*normals_C)[static_cast<std::size_t>(pv) * depth.width_px + pu]
                           : Eigen::Vector4f::Zero();
  if (config.distance_mode == DistanceMode::kPointToPlane && normal.w() > 0.5f) {
    const Eigen::Vector3f surface_C = pixelRay(pixel_u, pixel_v, camera.K) * d;
    sdf_m = normal.head<3>().dot(p_C - surface_C);
  }
  o.tsdf_m = std::min(sdf_m, truncation_m);

  float weight = config.weight_mode == WeightMode::kConstant ? 1.0f : 1.0f / (d * d);
  const float dropoff_start_m = config.dropoff_start_voxels * config.voxel_size_m;
  if (config.weight_dropoff && sdf_m < -dropoff_start_m) {
    weight *= (truncation_m + sdf_m) / (truncation_m - dropoff_start_m);
  }
  if (weight > 0.0f) o.weight = weight;
  return o;
}

void applyObservation(TsdfVoxel& voxel, const VoxelObservation& o, const ColorImage* color,
                      const MapConfig& config) {
  if (!(o.weight > 0.0f)) return;
  const float new_weight = voxel.weight + o.weight;
  voxel.tsdf_m = (voxel.tsdf_m * voxel.weight + o.tsdf_m * o.weight) / new_weight;
  if (color != nullptr) {
    voxel.color_rgba = blendColor(voxel.color_rgba, packedPixelColor(*color, o.u_px, o.v_px),
                                  voxel.weight, o.weight);
  }
  voxel.weight = std::min(new_weight, config.max_weight);
}

void integrateVoxelReference(TsdfVoxel& voxel, const Eigen::Vector3f& p_W, const DepthImage& depth,
                             const std::vector<Eigen::Vector4f>* normals_C, const ColorImage* color,
                             const FrameCamera& camera, const MapConfig& config) {
  applyObservation(voxel, observeVoxelReference(p_W, depth, normals_C, camera, config), color,
                   config);
}

std::vector<BlockIndex> integrateFrameReference(TsdfMap& map, const RgbdFrame& frame,
                                                const CameraIntrinsics& intrinsics, int threads) {
  intrinsics.validate();
  validateFrame(frame, intrinsics);
  const MapConfig& config = map.config();
  const FrameCamera camera = FrameCamera::from(intrinsics, frame.T_W_C);
  const std::vector<BlockIndex> touched = allocatedBlocksReference(frame.depth, camera, config);
  const std::vector<Eigen::Vector4f> normals_C =
      estimateNormalsReference(frame.depth, camera, config);
  std::vector<TsdfBlock*> blocks;
  blocks.reserve(touched.size());
  for (const BlockIndex& b : touched) blocks.push_back(&map.allocateBlock(b));

  // Blocks are independent.
  parallelForEach(touched.size(), std::max(1, threads), [&](std::size_t i) {
    integrateBlock(*blocks[i], touched[i], frame, normals_C, camera, config);
  });
  return touched;
}

}  // namespace strata
