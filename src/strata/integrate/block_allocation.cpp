#include "strata/integrate/block_allocation.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <unordered_set>

#include "strata/map/device_layout.h"

namespace strata {
namespace {

constexpr int kTilePx = static_cast<int>(gpu::kAllocationTilePx);
constexpr int kQuarterPx = kTilePx / 2;
constexpr float kSlabMarginBlocks = 1e-3f;  // as in allocate_blocks.comp

using BlockSet = std::unordered_set<BlockIndex, BlockIndexHash>;

int signOf(float x) { return (x > 0.0f) - (x < 0.0f); }

// Written out term by term in the shader's order so both round alike.
float dot3(const Eigen::Vector3f& a, const Eigen::Vector3f& b) {
  return a.x() * b.x() + a.y() * b.y() + a.z() * b.z();
}

Eigen::Vector3f rotate(const Eigen::Matrix3f& R, const Eigen::Vector3f& v) {
  return Eigen::Vector3f(R(0, 0) * v.x() + R(0, 1) * v.y() + R(0, 2) * v.z(),
                         R(1, 0) * v.x() + R(1, 1) * v.y() + R(1, 2) * v.z(),
                         R(2, 0) * v.x() + R(2, 1) * v.y() + R(2, 2) * v.z());
}

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

/// One frame's allocation state: the camera, the config's lengths and the set being filled.
struct Allocator {
  const FrameCamera& camera;
  const MapConfig& config;
  Eigen::Matrix3f R_W_C;
  Eigen::Vector3f origin_W;
  float truncation_m;
  float block_size_m;
  BlockSet blocks;

  Allocator(const FrameCamera& c, const MapConfig& m)
      : camera(c),
        config(m),
        R_W_C(c.T_W_C.topLeftCorner<3, 3>()),
        origin_W(c.T_W_C.topRightCorner<3, 1>()),
        truncation_m(m.truncationDistance()),
        block_size_m(m.blockSize()) {}

  void insert(const BlockIndex& b) {
    if (blockIndexInRange(b)) blocks.insert(b);
  }

  void marchRay(int u, int v, float depth, bool free_space) {
    const Eigen::Vector3f ray_C = pixelRay(static_cast<float>(u), static_cast<float>(v), camera.K);
    const float range_m = depth * ray_C.norm();
    const Eigen::Vector3f dir_W = R_W_C * ray_C.normalized();
    float t_start = std::max(range_m - truncation_m, 0.0f);
    if (free_space) t_start = std::min(t_start, config.min_depth_m * ray_C.norm());
    traverseBlocks(origin_W, dir_W, t_start, range_m + truncation_m, block_size_m,
                   [&](const BlockIndex& b) { insert(b); });
  }

  static Eigen::Vector3f sideNormal(const Eigen::Vector3f& a, const Eigen::Vector3f& b,
                                    const Eigen::Vector3f& centre) {
    Eigen::Vector3f n = a.cross(b);
    const float len = std::sqrt(dot3(n, n));
    if (!(len > 0.0f)) return Eigen::Vector3f::Zero();
    n = n / len;
    return dot3(n, centre) < 0.0f ? Eigen::Vector3f(-n) : n;
  }

  /// Blocks meeting the frustum slab of pixels [p0, p1] between depths z_min -/+ truncation.
  void insertSlab(int u0, int v0, int u1, int v1, float z_min, float z_max) {
    const float z_near = std::max(z_min - truncation_m, 0.0f);
    const float z_far = z_max + truncation_m;
    const auto ray = [&](int u, int v) {
      return pixelRay(static_cast<float>(u), static_cast<float>(v), camera.K);
    };
    const std::array<Eigen::Vector3f, 4> r = {ray(u0, v0), ray(u1, v0), ray(u0, v1), ray(u1, v1)};
    Eigen::Vector3f lo = Eigen::Vector3f::Constant(3.0e38f);
    Eigen::Vector3f hi = Eigen::Vector3f::Constant(-3.0e38f);
    for (const Eigen::Vector3f& ri : r) {
      const Eigen::Vector3f near_W = rotate(R_W_C, ri * z_near) + origin_W;
      const Eigen::Vector3f far_W = rotate(R_W_C, ri * z_far) + origin_W;
      lo = lo.cwiseMin(near_W.cwiseMin(far_W));
      hi = hi.cwiseMax(near_W.cwiseMax(far_W));
    }
    const float margin_m = kSlabMarginBlocks * block_size_m;
    const Eigen::Vector3i b_lo =
        ((lo.array() - margin_m) / block_size_m).floor().cast<int>().matrix();
    const Eigen::Vector3i b_hi =
        ((hi.array() + margin_m) / block_size_m).floor().cast<int>().matrix();

    const Eigen::Vector3f centre_C = (r[0] + r[3]) * 0.5f;
    const std::array<Eigen::Vector3f, 4> n_C = {
        sideNormal(r[0], r[1], centre_C), sideNormal(r[1], r[3], centre_C),
        sideNormal(r[3], r[2], centre_C), sideNormal(r[2], r[0], centre_C)};
    std::array<Eigen::Vector3f, 6> n_W;
    std::array<float, 6> d_W{};
    for (int i = 0; i < 4; ++i) {
      n_W[i] = rotate(R_W_C, n_C[i]);
      d_W[i] = -dot3(n_W[i], origin_W);
    }
    const Eigen::Vector3f axis_W = R_W_C.col(2);
    n_W[4] = axis_W;
    d_W[4] = -z_near - dot3(axis_W, origin_W);
    n_W[5] = -axis_W;
    d_W[5] = z_far + dot3(axis_W, origin_W);

    const float half_m = 0.5f * block_size_m;
    for (int z = b_lo.z(); z <= b_hi.z(); ++z) {
      for (int y = b_lo.y(); y <= b_hi.y(); ++y) {
        for (int x = b_lo.x(); x <= b_hi.x(); ++x) {
          const Eigen::Vector3f centre_W =
              (Eigen::Vector3f(static_cast<float>(x), static_cast<float>(y),
                               static_cast<float>(z)).array() + 0.5f) * block_size_m;
          bool inside = true;
          for (int f = 0; f < 6 && inside; ++f) {
            const Eigen::Vector3f& n = n_W[f];
            const float reach = half_m * (std::abs(n.x()) + std::abs(n.y()) + std::abs(n.z()));
            inside = dot3(n, centre_W) + d_W[f] + reach >= -margin_m;
          }
          if (inside) insert(BlockIndex(x, y, z));
        }
      }
    }
  }
};

bool freeSpacePixel(const MapConfig& config, int u, int v) {
  const int stride = config.allocate_free_space ? static_cast<int>(config.free_space_pixel_stride)
                                                : 0;
  return stride > 0 && u % stride == 0 && v % stride == 0;
}

std::vector<BlockIndex> sortedBlocks(const BlockSet& set) {
  std::vector<BlockIndex> sorted(set.begin(), set.end());
  std::sort(sorted.begin(), sorted.end(), [](const BlockIndex& a, const BlockIndex& b) {
    if (a.z() != b.z()) return a.z() < b.z();
    if (a.y() != b.y()) return a.y() < b.y();
    return a.x() < b.x();
  });
  return sorted;
}

struct DepthRange {
  float lo = 3.0e38f;
  float hi = -3.0e38f;
  bool empty() const { return lo > hi; }
  float span() const { return hi - lo; }
  void add(float d) {
    lo = std::min(lo, d);
    hi = std::max(hi, d);
  }
};

void allocateTile(const DepthImage& depth, int u0, int v0, float max_slab_m, Allocator& a) {
  const MapConfig& config = a.config;
  const int u1 = std::min(u0 + kTilePx, depth.width_px) - 1;
  const int v1 = std::min(v0 + kTilePx, depth.height_px) - 1;
  std::array<DepthRange, 4> quarter;
  for (int v = v0; v <= v1; ++v) {
    for (int u = u0; u <= u1; ++u) {
      const float d = depth.at(u, v);
      if (!depthValid(d, config.min_depth_m, config.max_depth_m)) continue;
      quarter[(u - u0 >= kQuarterPx ? 1 : 0) + (v - v0 >= kQuarterPx ? 2 : 0)].add(d);
      if (freeSpacePixel(config, u, v)) a.marchRay(u, v, d, true);
    }
  }
  DepthRange whole;
  whole.lo = std::min(std::min(quarter[0].lo, quarter[1].lo), std::min(quarter[2].lo, quarter[3].lo));
  whole.hi = std::max(std::max(quarter[0].hi, quarter[1].hi), std::max(quarter[2].hi, quarter[3].hi));
  if (whole.empty()) return;
  if (whole.span() <= max_slab_m) {
    a.insertSlab(u0, v0, u1, v1, whole.lo, whole.hi);
    return;
  }
  for (int q = 0; q < 4; ++q) {
    if (quarter[q].empty()) continue;
    const int qu0 = u0 + (q & 1) * kQuarterPx;
    const int qv0 = v0 + (q >> 1) * kQuarterPx;
    const int qu1 = std::min(qu0 + kQuarterPx - 1, u1);
    const int qv1 = std::min(qv0 + kQuarterPx - 1, v1);
    if (quarter[q].span() <= max_slab_m) {
      a.insertSlab(qu0, qv0, qu1, qv1, quarter[q].lo, quarter[q].hi);
      continue;
    }
    for (int v = qv0; v <= qv1; ++v) {
      for (int u = qu0; u <= qu1; ++u) {
        const float d = depth.at(u, v);
        if (depthValid(d, config.min_depth_m, config.max_depth_m)) a.marchRay(u, v, d, false);
      }
    }
  }
}

}  // namespace

float maxSlabDepth(const MapConfig& config) { return config.blockSize(); }

std::vector<BlockIndex> bandBlocksReference(const DepthImage& depth, const FrameCamera& camera,
                                            const MapConfig& config) {
  Allocator a(camera, config);
  for (int v = 0; v < depth.height_px; ++v) {
    for (int u = 0; u < depth.width_px; ++u) {
      const float d = depth.at(u, v);
      if (depthValid(d, config.min_depth_m, config.max_depth_m)) {
        a.marchRay(u, v, d, freeSpacePixel(config, u, v));
      }
    }
  }
  return sortedBlocks(a.blocks);
}

std::vector<BlockIndex> allocatedBlocksReference(const DepthImage& depth, const FrameCamera& camera,
                                                 const MapConfig& config) {
  Allocator a(camera, config);
  const float max_slab_m = maxSlabDepth(config);
  for (int v0 = 0; v0 < depth.height_px; v0 += kTilePx) {
    for (int u0 = 0; u0 < depth.width_px; u0 += kTilePx) allocateTile(depth, u0, v0, max_slab_m, a);
  }
  return sortedBlocks(a.blocks);
}

}  // namespace strata
