#pragma once
// The ESDF on the device: exact signed Euclidean distance to the nearest site, propagated from the
// TSDF, kept up to date incrementally. Reference: computeEsdfReference (exact nearest site).
// Device algorithm (why: shaders/esdf_edt_pass.comp): the update box is gathered into a dense
// working box, sites marked, an exact separable Euclidean transform run along x, y and z keeping
// each voxel's nearest-site offset, and the result scattered back to the allocated blocks.
// Thread safety: not thread safe.
#include <cstdint>
#include <vector>

#include "strata/map/device_tsdf_map.h"
#include "strata/map/esdf_layer.h"
#include "strata/map/tsdf_map.h"
#include "strata/vk/vk.h"

namespace strata {

/// Exact ESDF of every voxel of every allocated block of `tsdf` on the host (the specification):
/// sites = observed voxels with |tsdf| <= threshold; distance = Euclidean distance between voxel
/// centres to the nearest site (capped at max_distance), sign of the voxel's own TSDF; unobserved
/// voxels carry no observed flag (their distance is the unsigned distance to the nearest site).
EsdfMap computeEsdfReference(const TsdfMap& tsdf, const EsdfConfig& config);

struct EsdfUpdateStats {
  double device_ms = 0.0;              // timestamp queries, all ESDF passes
  double wall_ms = 0.0;
  std::uint64_t voxels_updated = 0;    // voxels whose ESDF was recomputed
  std::uint32_t blocks_updated = 0;
  bool full = false;                   // a full recomputation (not incremental)
  std::uint32_t slabs = 0;             // dense working boxes it ran in (> 1: cut to fit memory)
};

class DeviceEsdf {
 public:
  /// `tsdf` must outlive this object; the ESDF pool follows its slots (grown on update).
  DeviceEsdf(vk::Context& context, DeviceTsdfMap& tsdf, const EsdfConfig& config = {});
  ~DeviceEsdf();

  const EsdfConfig& config() const { return config_; }
  /// Blocks whose TSDF changed since the last update (e.g. the touched blocks of fused frames).
  void markDirty(const std::vector<BlockIndex>& blocks);
  /// Recomputes every allocated block.
  EsdfUpdateStats updateAll();
  /// Recomputes only the blocks the dirty blocks can influence (within max distance), including
  /// raising distances where sites disappeared. Equals updateAll() on those blocks. After
  /// DeviceTsdfMap::upload replaced the map, call updateAll() instead.
  EsdfUpdateStats updateIncremental();
  /// Explicit device->host copy of the ESDF layer (blocks keyed like the TSDF map).
  void download(EsdfMap& out);

  /// The ESDF voxel pool: block slot s holds EsdfVoxel[512] at s * 4096 bytes (device address).
  const vk::Buffer& pool() const;
  /// Slots [0, n) hold a computed ESDF (the blocks known at the last update).
  std::uint32_t computedBlockCount() const;
  /// Device memory for the dense working box of one update (default 512 MiB; a larger box is cut
  /// into slabs, each exact) and the per-line scratch of the transform (default 64 MiB; larger
  /// boxes run in several dispatches).
  void setWorkingMemoryBudget(std::uint64_t box_bytes, std::uint64_t scratch_bytes);
  /// Buffers (working box, pools) larger than this are reached by device address instead of a
  /// binding (default and upper bound: the device's maxStorageBufferRange). Tests lower it to
  /// cover the device-address path.
  void setBindingLimit(std::uint64_t bytes);
  DeviceTsdfMap& tsdf() { return tsdf_; }

 private:
  struct Impl;
  vk::Context& context_;
  DeviceTsdfMap& tsdf_;
  EsdfConfig config_;
  std::unique_ptr<Impl> impl_;
};

}  // namespace strata
