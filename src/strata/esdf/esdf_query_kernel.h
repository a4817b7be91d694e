#pragma once
// Device ESDF queries (shaders/esdf_query_points.comp): distance, gradient and status per point,
// and optionally the sphere collision flag, for a batch of points in one dispatch. Semantics are
// those of the host EsdfQuery (esdf_query.h), which the tests hold it to.
// Thread safety: not thread safe (one kernel per thread, like the Vulkan context it uses).
#include <Eigen/Core>
#include <cstdint>
#include <optional>
#include <vector>

#include "strata/esdf/esdf.h"
#include "strata/esdf/esdf_query.h"
#include "strata/vk/vk.h"

namespace strata {

class DeviceTsdfMap;

struct EsdfSphereTest {
  float radius_m = 0.0f;
  float margin_m = 0.0f;
  UnknownPolicy policy = UnknownPolicy::kOccupied;
};

struct EsdfQueryResult {
  std::vector<EsdfSample> samples;        // one per point
  std::vector<std::uint8_t> sphere_free;  // one per point when a sphere test was asked for
  double device_ms = 0.0;                 // the dispatch (timestamp queries)
};

/// The ESDF on the device as the query kernel sees it: the TSDF block hash (block -> slot), the
/// ESDF pool (slot s at s * 4096 bytes), how many slots hold a computed ESDF (later slots read as
/// unallocated) and the config. DeviceEsdf provides them all.
struct DeviceEsdfView {
  DeviceTsdfMap& tsdf;
  const vk::Buffer& esdf_pool;
  std::uint32_t computed_blocks;
  EsdfConfig config;
};

class EsdfQueryKernel {
 public:
  explicit EsdfQueryKernel(vk::Context& context);

  /// Queries `points_W` (any count, 0 included; non-finite points come back kOutside / not free).
  /// Host->device and device->host copies happen here (mapped buffers, no hidden staging).
  EsdfQueryResult run(const DeviceEsdfView& esdf, const std::vector<Eigen::Vector3f>& points_W,
                      const std::optional<EsdfSphereTest>& spheres = std::nullopt);

  /// The pool is read through a storage-buffer binding when it fits one binding's range (faster on
  /// lavapipe), else by device address. On: always by address (so tests cover both paths).
  void setForcePoolByAddress(bool on) { force_pool_by_address_ = on; }

  /// The same on a DeviceEsdf (inline so that code not using DeviceEsdf need not link it).
  EsdfQueryResult run(DeviceEsdf& esdf, const std::vector<Eigen::Vector3f>& points_W,
                      const std::optional<EsdfSphereTest>& spheres = std::nullopt) {
    return run(DeviceEsdfView{esdf.tsdf(), esdf.pool(), esdf.computedBlockCount(), esdf.config()},
               points_W, spheres);
  }

 private:
  void ensureCapacity(std::size_t points);
  /// The pipeline reading the pool through its binding (false) or by device address (true).
  const vk::ComputePipeline& pipeline(bool pool_by_address);

  vk::Context& context_;
  vk::ComputePipeline pipelines_[2];  // made on first use
  vk::Buffer empty_pool_;  // bound when the ESDF has no pool yet (a binding needs a buffer)
  vk::Buffer points_;
  vk::Buffer samples_;
  vk::Buffer flags_;
  vk::TimestampQueries timer_;
  std::size_t capacity_ = 0;
  bool force_pool_by_address_ = false;
};

}  // namespace strata
