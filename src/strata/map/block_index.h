#pragma once
// Block addressing shared by host and device (mirrors shaders/common/map_layout.glsl).
// Voxel (i,j,k) of the global grid has its centre at ((i,j,k) + 0.5) * voxel_size_m; block b holds
// global voxels b*8 .. b*8+7 on each axis; inside a block voxels are stored x fastest.
#include <Eigen/Core>
#include <cstdint>
#include <functional>

namespace strata {

inline constexpr int kBlockEdge = 8;
inline constexpr int kVoxelsPerBlock = kBlockEdge * kBlockEdge * kBlockEdge;
/// Each block coordinate is stored in 21 bits with this bias: +-2^20 blocks per axis.
inline constexpr std::int32_t kBlockCoordBias = 1 << 20;
inline constexpr std::uint64_t kEmptyBlockKey = ~std::uint64_t{0};

using BlockIndex = Eigen::Vector3i;
using GlobalVoxelIndex = Eigen::Vector3i;

inline bool blockIndexInRange(const BlockIndex& b) {
  return (b.array() >= -kBlockCoordBias).all() && (b.array() < kBlockCoordBias).all();
}

/// 63-bit key: x | y << 21 | z << 42, each biased; never equals kEmptyBlockKey.
inline std::uint64_t packBlockKey(const BlockIndex& b) {
  const auto x = static_cast<std::uint64_t>(b.x() + kBlockCoordBias);
  const auto y = static_cast<std::uint64_t>(b.y() + kBlockCoordBias);
  const auto z = static_cast<std::uint64_t>(b.z() + kBlockCoordBias);
  return x | (y << 21) | (z << 42);
}

inline BlockIndex unpackBlockKey(std::uint64_t key) {
  const auto mask = (std::uint64_t{1} << 21) - 1;
  return BlockIndex(static_cast<int>(key & mask) - kBlockCoordBias,
                    static_cast<int>((key >> 21) & mask) - kBlockCoordBias,
                    static_cast<int>((key >> 42) & mask) - kBlockCoordBias);
}

/// Hash of a packed key into a power-of-two table (same function as the shaders).
inline std::uint32_t hashBlockKey(std::uint64_t key) {
  std::uint32_t lo = static_cast<std::uint32_t>(key);
  std::uint32_t hi = static_cast<std::uint32_t>(key >> 32);
  std::uint32_t h = lo * 0x9E3779B1u ^ (hi * 0x85EBCA77u);
  h ^= h >> 15;
  h *= 0x2C1B3C6Du;
  h ^= h >> 12;
  return h;
}

inline int floorDiv(int a, int b) { return (a >= 0) ? a / b : -((-a + b - 1) / b); }

inline BlockIndex blockOfVoxel(const GlobalVoxelIndex& v) {
  return BlockIndex(floorDiv(v.x(), kBlockEdge), floorDiv(v.y(), kBlockEdge),
                    floorDiv(v.z(), kBlockEdge));
}

/// Linear index of a voxel inside its block (x fastest).
inline int linearVoxelIndex(int x, int y, int z) { return x + kBlockEdge * (y + kBlockEdge * z); }

inline Eigen::Vector3f voxelCenter(const GlobalVoxelIndex& v, float voxel_size_m) {
  return (v.cast<float>() + Eigen::Vector3f::Constant(0.5f)) * voxel_size_m;
}

struct BlockIndexHash {
  std::size_t operator()(const BlockIndex& b) const { return hashBlockKey(packBlockKey(b)); }
};

}  // namespace strata
