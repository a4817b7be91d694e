#pragma once
// The host-side TSDF map: the readable reference representation. The device map (DeviceTsdfMap)
// downloads into it; meshing, map files and the C++ reference kernels work on it.
#include <array>
#include <cstdint>
#include <unordered_map>
#include <vector>

#include "strata/map/block_index.h"
#include "strata/map/map_config.h"

namespace strata {

/// One TSDF voxel, 12 bytes; mirrors `TsdfVoxel` in shaders/common/map_layout.glsl.
struct TsdfVoxel {
  float tsdf_m = 0.0f;          // truncated signed distance along the ray, metres (+ in front)
  float weight = 0.0f;          // accumulated weight; 0 = never observed
  std::uint32_t color_rgba = 0; // r | g << 8 | b << 16 (alpha unused)
};
static_assert(sizeof(TsdfVoxel) == 12, "TsdfVoxel must match the std430 layout in the shaders");

using TsdfBlock = std::array<TsdfVoxel, kVoxelsPerBlock>;

inline std::uint32_t packRgb(std::uint8_t r, std::uint8_t g, std::uint8_t b) {
  return std::uint32_t{r} | (std::uint32_t{g} << 8) | (std::uint32_t{b} << 16);
}

class TsdfMap {
 public:
  explicit TsdfMap(const MapConfig& config);

  const MapConfig& config() const { return config_; }
  std::size_t blockCount() const { return blocks_.size(); }

  /// nullptr when the block is not allocated.
  const TsdfBlock* findBlock(const BlockIndex& b) const;
  TsdfBlock* findBlock(const BlockIndex& b);
  /// Returns the block, allocating it (all voxels unobserved) when absent.
  TsdfBlock& allocateBlock(const BlockIndex& b);

  /// Voxel at a global index, nullptr when its block is not allocated.
  const TsdfVoxel* findVoxel(const GlobalVoxelIndex& v) const;
  /// Voxel at a global index, its block allocated (all voxels unobserved) when absent.
  TsdfVoxel& allocateVoxel(const GlobalVoxelIndex& v);

  /// All block indices, sorted (z, y, x) so iteration and files are deterministic.
  std::vector<BlockIndex> sortedBlockIndices() const;

  const std::unordered_map<BlockIndex, TsdfBlock, BlockIndexHash>& blocks() const {
    return blocks_;
  }
  void clear() { blocks_.clear(); }

 private:
  MapConfig config_;
  std::unordered_map<BlockIndex, TsdfBlock, BlockIndexHash> blocks_;
};

}  // namespace strata
