#pragma once
// The ESDF layer: per voxel of every allocated block, the signed Euclidean distance to the nearest
// site (an observed TSDF voxel on the surface) and the offset to that site, so distance and
// gradient are exact. Shares the block index (and pool slots) with the TSDF layer.
// Mirrors `EsdfVoxel` in shaders/common/esdf_layout.glsl.
#include <array>
#include <cstdint>
#include <string>
#include <unordered_map>

#include "strata/map/block_index.h"

namespace strata {

struct EsdfConfig {
  /// Distances are exact up to this; farther voxels hold +-max_distance_m and no site.
  float max_distance_m = 2.0f;
  /// A TSDF voxel is a site (an obstacle surface voxel) when observed and |tsdf| <= this many
  /// voxels. One voxel keeps thin walls closed without thickening surfaces much.
  float site_threshold_voxels = 1.0f;
  /// TSDF voxels with less weight are unknown (neither site nor free).
  float min_weight = 1e-3f;
  /// TSDF layer of the device map the ESDF follows (0: the default layer).
  int tsdf_layer = 0;

  /// Throws InputError naming the bad field.
  void validate(float voxel_size_m) const;
};

/// 8 bytes: signed distance (negative inside, from the TSDF sign) and packed flags + site offset.
struct EsdfVoxel {
  float distance_m = 0.0f;
  std::uint32_t site_and_flags = 0;  // see the accessors below
};
static_assert(sizeof(EsdfVoxel) == 8, "EsdfVoxel must match the std430 layout in the shaders");

inline constexpr std::uint32_t kEsdfObservedBit = 1u << 31;  // the voxel is known (TSDF observed)
inline constexpr std::uint32_t kEsdfHasSiteBit = 1u << 30;   // a site lies within max distance
inline constexpr int kEsdfOffsetBits = 10;                   // per axis, two's complement
inline constexpr int kEsdfMaxOffset = (1 << (kEsdfOffsetBits - 1)) - 1;  // 511 voxels

inline bool esdfObserved(const EsdfVoxel& v) { return (v.site_and_flags & kEsdfObservedBit) != 0; }
inline bool esdfHasSite(const EsdfVoxel& v) { return (v.site_and_flags & kEsdfHasSiteBit) != 0; }

/// Offset (voxels) from the voxel to its nearest site; each component within +-kEsdfMaxOffset.
inline std::uint32_t packSiteOffset(const Eigen::Vector3i& offset) {
  const std::uint32_t mask = (1u << kEsdfOffsetBits) - 1;
  return (static_cast<std::uint32_t>(offset.x()) & mask) |
         ((static_cast<std::uint32_t>(offset.y()) & mask) << kEsdfOffsetBits) |
         ((static_cast<std::uint32_t>(offset.z()) & mask) << (2 * kEsdfOffsetBits));
}

inline Eigen::Vector3i unpackSiteOffset(std::uint32_t packed) {
  auto component = [](std::uint32_t bits) {
    const int value = static_cast<int>(bits & ((1u << kEsdfOffsetBits) - 1));
    return value > kEsdfMaxOffset ? value - (1 << kEsdfOffsetBits) : value;
  };
  return Eigen::Vector3i(component(packed), component(packed >> kEsdfOffsetBits),
                         component(packed >> (2 * kEsdfOffsetBits)));
}

using EsdfBlock = std::array<EsdfVoxel, kVoxelsPerBlock>;
/// Bytes per ESDF block (a slot's stride in the device's ESDF pool).
inline constexpr std::uint64_t kEsdfBlockBytes = sizeof(EsdfBlock);

/// Host copy of the ESDF layer (downloaded from the device, or computed by the reference).
struct EsdfMap {
  float voxel_size_m = 0.02f;
  EsdfConfig config;
  std::unordered_map<BlockIndex, EsdfBlock, BlockIndexHash> blocks;

  /// nullptr when the voxel's block is not allocated.
  const EsdfVoxel* findVoxel(const GlobalVoxelIndex& v) const;
};

}  // namespace strata
