#include "integrate/block_allocation.h"

#include <algorithm>
#include <cmath>
#include <unordered_set>

namespace strata {
namespace {

int signOf(float x) { return (x > 0.0f) - (x < 0.0f); }

/// Amanatides-Woo traversal of the block grid along the ray segment [t_start, t_end]; mirrors the
/// loop in allocate_blocks.comp step for step.
template <typename Visit>
void traverseBlocks(const Eigen::Vector3f& origin_W, const Eigen::Vector3f& dir_W, float t_start,
                    float t_end, float block_size_m, Visit&& visit) {
  const Eigen::Vector3f start_b = (origin_W + dir_W * t_start) / block_size_m;
  Eigen::Vector3i block = start_b.array().floor().cast<int>();
  const Eigen::Vector3i end_block =
      ((origin_W + dir_W * t_end) / block_size_m).array().floor().cast<int>();
  const Eigen::Vector3i step(signOf(dir_W.x()), signOf(dir_W.y()), signOf(dir_W.z()));
  const Eigen::Vector3f inv_dir = dir_W.cwiseAbs().cwiseMax(1e-12f).cwiseInverse();
  const Eigen::Vector3f next_boundary =
      block.cast<float>() + step.cast<float>().cwiseMax(0.0f);
  Eigen::Vector3f t_max = ((next_boundary - start_b).cwiseAbs().cwiseProduct(inv_dir) *
                           block_size_m).array() + t_start;
  const Eigen::Vector3f t_delta = inv_dir * block_size_m;
  const int max_steps = 3 * (static_cast<int>(std::ceil((t_end - t_start) / block_size_m)) + 2);
  for (int s = 0; s < max_steps; ++s) {
    visit(block);
    if (block == end_block) break;
    int axis = 2;
    if (t_max.x() < t_max.y() && t_max.x() < t_max.z()) {
      axis = 0;
    } else if (t_max.y() < t_max.z()) {
      axis = 1;
    }
    if (t_max[axis] > t_end) break;
    block[axis] += step[axis];
    t_max[axis] += t_delta[axis];
  }
}

}  // namespace

std::vector<BlockIndex> touchedBlocksReference(const DepthImage& depth, const FrameCamera& camera,
                                               const MapConfig& config) {
  const float truncation_m = config.truncationDistance();
  const float block_size_m = config.blockSize();
  const Eigen::Matrix3f R_W_C = camera.T_W_C.topLeftCorner<3, 3>();
  const Eigen::Vector3f origin_W = camera.T_W_C.topRightCorner<3, 1>();
  std::unordered_set<BlockIndex, BlockIndexHash> touched;
  for (int v = 0; v < depth.height_px; ++v) {
    for (int u = 0; u < depth.width_px; ++u) {
      const float d = depth.at(u, v);
      if (!depthValid(d, config.min_depth_m, config.max_depth_m)) continue;
      const Eigen::Vector3f ray_C = pixelRay(static_cast<float>(u), static_cast<float>(v), camera.K);
      const float range_m = d * ray_C.norm();
      const Eigen::Vector3f dir_W = R_W_C * ray_C.normalized();
      float t_start = std::max(range_m - truncation_m, 0.0f);
      const std::uint32_t stride = config.allocate_free_space ? config.free_space_pixel_stride : 0;
      if (stride > 0 && u % stride == 0 && v % stride == 0) {
        t_start = std::min(t_start, config.min_depth_m * ray_C.norm());
      }
      traverseBlocks(origin_W, dir_W, t_start, range_m + truncation_m, block_size_m,
                     [&](const BlockIndex& b) {
                       if (blockIndexInRange(b)) touched.insert(b);
                     });
    }
  }
  std::vector<BlockIndex> sorted(touched.begin(), touched.end());
  std::sort(sorted.begin(), sorted.end(), [](const BlockIndex& a, const BlockIndex& b) {
    if (a.z() != b.z()) return a.z() < b.z();
    if (a.y() != b.y()) return a.y() < b.y();
    return a.x() < b.x();
  });
  return sorted;
}

}  // namespace strata
