#pragma once
// Map files (.strata): the whole map (config and every layer), versioned and checksummed, written
// atomically. Layout (little-endian):
//   "STRATAMP" | u32 format version | u32 config bytes | config fields | u32 layer count |
//   per layer: u32 layer id, u32 bytes per voxel, u64 block count, blocks sorted (z, y, x), each
//   i32 x, y, z then the voxels | u32 CRC-32 of everything before it.
// Saving is deterministic: save -> load -> save gives identical bytes.
#include <cstdint>
#include <string>
#include <vector>

#include "strata/map/tsdf_map.h"

namespace strata {

inline constexpr std::uint32_t kMapFormatVersion = 1;
inline constexpr std::uint32_t kLayerTsdf = 1;

std::vector<std::uint8_t> serializeMap(const TsdfMap& map);
/// Throws InputError naming `what` (a path) and the problem: bad magic, other version, truncated,
/// checksum mismatch, invalid config, unknown layer.
TsdfMap deserializeMap(const std::vector<std::uint8_t>& bytes, const std::string& what);

void saveMap(const TsdfMap& map, const std::string& path);
TsdfMap loadMap(const std::string& path);

}  // namespace strata
