#pragma once
// Map files (.strata): the whole map (config and every layer), versioned and checksummed, written
// atomically. Layout (little-endian):
//   "STRATAMP" | u32 format version | u32 config bytes | config fields |
//   [version 2: u32 record bytes | the session record (MapSessionRecord's fields)] |
//   u32 layer count | per layer: u32 layer id, u32 bytes per voxel, u64 block count, blocks sorted
//   (z, y, x), each i32 x, y, z then the voxels | u32 CRC-32 of everything before it.
// Version 1 holds one map (layer 1). Version 2 is a mapper's state with change detection: the
// live layer (layer 1), the static estimate while a session is open (layer 2) and where the
// sessions stand, so a mapper restarted from it continues exactly (Mapper::resume). Plain maps
// are still written as version 1; every reader reads both and sees layer 1 as the map.
// Saving is deterministic: save -> load -> save gives identical bytes.
// Thread safety: free functions without shared state.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "strata/map/tsdf_map.h"

namespace strata {

inline constexpr std::uint32_t kMapFormatVersion = 1;          // a plain map
inline constexpr std::uint32_t kMapStateFormatVersion = 2;     // a mapper's state
inline constexpr std::uint32_t kLayerTsdf = 1;                 // the map (the live layer)
inline constexpr std::uint32_t kLayerStaticTsdf = 2;           // S while a session is open

/// Where a change-detecting mapper's sessions stood when it saved.
struct MapSessionRecord {
  std::uint32_t sessions_ended = 0;  // merged into the static estimate S
  bool session_open = false;         // layer 1 is then that session's own layer, layer 2 is S
  std::uint64_t session_frames = 0;  // fused into the open session
  std::uint64_t frames = 0;          // fused in all sessions
};

/// What a map file holds. `static_map` is present exactly when sessions->session_open; its config
/// is map's.
struct MapFileContents {
  TsdfMap map;                                // layer 1: what every reader of the file sees
  std::optional<TsdfMap> static_map;          // layer 2
  std::optional<MapSessionRecord> sessions;   // version 2 only
};

std::vector<std::uint8_t> serializeMap(const TsdfMap& map);
/// Layer 1 of a file of either version. Throws InputError naming `what` (a path) and the problem:
/// bad magic, other version, truncated, checksum mismatch, invalid config, unknown layer.
TsdfMap deserializeMap(const std::vector<std::uint8_t>& bytes, const std::string& what);

/// Version 2 when `contents.sessions` is set, else version 1 (static_map must then be absent).
/// InputError for contents that break the rules above (a static layer without an open session,
/// another config).
std::vector<std::uint8_t> serializeMapFile(const MapFileContents& contents);
/// Everything in a file of either version; the errors of deserializeMap, and a static layer that
/// does not match the record.
MapFileContents deserializeMapFile(const std::vector<std::uint8_t>& bytes, const std::string& what);

void saveMap(const TsdfMap& map, const std::string& path);
TsdfMap loadMap(const std::string& path);
void saveMapFile(const MapFileContents& contents, const std::string& path);
MapFileContents loadMapFile(const std::string& path);

}  // namespace strata
