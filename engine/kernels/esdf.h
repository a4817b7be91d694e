#pragma once
// The ESDF on the device: exact signed Euclidean distance to the nearest site, propagated from the
// TSDF, kept up to date incrementally. Reference: computeEsdfReference (exact nearest site).
// Thread safety: not thread safe.
#include <cstdint>
#include <vector>

#include "kernels/device_tsdf_map.h"
#include "map/esdf_layer.h"
#include "map/tsdf_map.h"
#include "vk/vk.h"

namespace strata {

/// Exact ESDF of every voxel of every allocated block of `tsdf` on the host (the specification):
/// sites = observed voxels with |tsdf| <= threshold; distance = Euclidean distance between voxel
/// centres to the nearest site (capped at max_distance), sign of the voxel's own TSDF; unobserved
/// voxels carry no observed flag.
EsdfMap computeEsdfReference(const TsdfMap& tsdf, const EsdfConfig& config);

struct EsdfUpdateStats {
  double device_ms = 0.0;              // timestamp queries, all ESDF passes
  double wall_ms = 0.0;
  std::uint64_t voxels_updated = 0;    // voxels whose ESDF was recomputed
  std::uint32_t blocks_updated = 0;
  bool full = false;                   // a full recomputation (not incremental)
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
  /// raising distances where sites disappeared. Equals updateAll() on those blocks.
  EsdfUpdateStats updateIncremental();
  /// Explicit device->host copy of the ESDF layer (blocks keyed like the TSDF map).
  void download(EsdfMap& out);

  /// The ESDF voxel pool: block slot s holds EsdfVoxel[512] at s * 4096 bytes (device address).
  const vk::Buffer& pool() const;
  DeviceTsdfMap& tsdf() { return tsdf_; }

 private:
  struct Impl;
  vk::Context& context_;
  DeviceTsdfMap& tsdf_;
  EsdfConfig config_;
  std::unique_ptr<Impl> impl_;
};

}  // namespace strata
