#pragma once
// Collision checks of a spherical robot against the ESDF, in batches: every planner of
// strata::plan asks through this interface, so a planner runs the same on the host copy of the
// ESDF (HostCollisionChecker, EsdfQuery) or on the device (DeviceCollisionChecker, the
// esdf_query_points kernel: one dispatch per batch, no download of the map).
//
// Semantics are those of esdf_query.h: a sphere (c, r) is free when no obstacle voxel centre lies
// within r (unknown voxels are obstacles under UnknownPolicy::kOccupied); a segment is the capsule
// of radius r around it, tested as spheres at most h = half a voxel apart, each of radius
// sqrt(r^2 + (h/2)^2), which covers the capsule (the same radius for every sample, so all samples
// of a batch of segments go in one sphere batch; at most 1/8 voxel more conservative than
// EsdfQuery::isSegmentFree for r = 0, less for larger r). Both back ends give the same flags
// (tests hold them to each other).
// Thread safety: not thread safe (the device back end owns one kernel and its buffers); one
// checker per thread.
#include <Eigen/Core>
#include <cstdint>
#include <vector>

#include "strata/esdf/esdf_query.h"
#include "strata/esdf/esdf_query_kernel.h"

namespace strata {
class DeviceEsdf;
namespace vk {
class Context;
}
}  // namespace strata

namespace strata::plan {

class CollisionChecker {
 public:
  virtual ~CollisionChecker() = default;

  /// One flag per centre (1: the sphere of radius_m is free).
  virtual std::vector<std::uint8_t> spheresFree(const std::vector<Eigen::Vector3f>& centres_W,
                                                float radius_m, UnknownPolicy unknown) = 0;
  /// Distance, gradient and status per point (esdf_query.h).
  virtual std::vector<EsdfSample> sample(const std::vector<Eigen::Vector3f>& points_W) = 0;
  /// Voxel size of the ESDF (metres).
  virtual float voxelSize() const = 0;
  /// Largest radius a sphere test can pass (the ESDF's max distance; larger spheres are never
  /// free).
  virtual float maxDistance() const = 0;

  /// One flag per segment (1: its capsule is free): every sample of every segment in one batch.
  /// Non-finite ends or a negative radius: not free.
  std::vector<std::uint8_t> segmentsFree(const std::vector<EsdfSegment>& segments, float radius_m,
                                         UnknownPolicy unknown);
  bool segmentFree(const Eigen::Vector3f& a_W, const Eigen::Vector3f& b_W, float radius_m,
                   UnknownPolicy unknown);
  /// Every segment of the polyline (one point: a sphere; empty: free).
  bool pathFree(const std::vector<Eigen::Vector3f>& path_W, float radius_m, UnknownPolicy unknown);
  /// Smallest ESDF distance at samples every half voxel along the polyline (metres); a sample that
  /// is not known reads 0.
  float minClearance(const std::vector<Eigen::Vector3f>& path_W);

  /// Sphere tests run so far (segments count their samples).
  std::uint64_t spheresTested() const { return spheres_tested_; }

 protected:
  std::uint64_t spheres_tested_ = 0;
};

/// On a host copy of the ESDF (which must outlive the checker and not change while it is used).
class HostCollisionChecker final : public CollisionChecker {
 public:
  explicit HostCollisionChecker(const EsdfMap& esdf);
  std::vector<std::uint8_t> spheresFree(const std::vector<Eigen::Vector3f>& centres_W,
                                        float radius_m, UnknownPolicy unknown) override;
  std::vector<EsdfSample> sample(const std::vector<Eigen::Vector3f>& points_W) override;
  float voxelSize() const override { return query_.voxelSize(); }
  float maxDistance() const override { return query_.map().config.max_distance_m; }
  const EsdfQuery& query() const { return query_; }

 private:
  EsdfQuery query_;
};

/// On the device ESDF (a DeviceEsdf, e.g. Mapper::deviceEsdf(), which must outlive the checker).
/// Every batch is one dispatch of esdf_query_points; device time is summed in deviceMs().
class DeviceCollisionChecker final : public CollisionChecker {
 public:
  DeviceCollisionChecker(vk::Context& context, DeviceEsdf& esdf);
  /// Points the checker at another ESDF (e.g. after the mapper recreated it); the kernel is kept.
  void setEsdf(DeviceEsdf& esdf) { esdf_ = &esdf; }
  std::vector<std::uint8_t> spheresFree(const std::vector<Eigen::Vector3f>& centres_W,
                                        float radius_m, UnknownPolicy unknown) override;
  std::vector<EsdfSample> sample(const std::vector<Eigen::Vector3f>& points_W) override;
  float voxelSize() const override;
  float maxDistance() const override;
  double deviceMs() const { return device_ms_; }

 private:
  EsdfQueryKernel kernel_;
  DeviceEsdf* esdf_;
  double device_ms_ = 0.0;
};

}  // namespace strata::plan
