#pragma once
// Planner queries on the ESDF, on the host from a synchronised copy (EsdfMap, e.g. from
// DeviceEsdf::download). The device twin is EsdfQueryKernel (shaders/esdf_query_points.comp); both
// follow the semantics written here and the tests hold them to each other.
//
// Model. Voxel (i,j,k) covers [i,i+1) x [j,j+1) x [k,k+1) voxel sizes; its ESDF value is the signed
// distance from its centre to the nearest site centre (negative inside obstacles), exact up to
// max_distance_m (farther: +-max_distance_m, read as "at least"). A query point p lies in voxel
// floor(p / voxel_size). Status of p:
//   kKnown   the voxel is observed;
//   kUnknown its block is allocated but the voxel was never observed;
//   kOutside its block is not allocated, or p is not finite (NaN/inf) or beyond the block range.
// Distance and gradient: trilinear interpolation of the 8 voxel centres around p when all 8 are
// known (exact at voxel centres, continuous, the gradient is the interpolant's derivative); when p
// is known but a neighbour is not, the distance of p's own voxel and a zero gradient. Not known:
// distance 0 and gradient 0 (reads as "touching an obstacle" to a planner that ignores status).
// The gradient is unit-free (metres per metre, |g| ~ 1) and points away from obstacles.
//
// Collision (R = radius + margin, both metres). Obstacles are the site and inside voxel centres;
// under UnknownPolicy::kOccupied every unknown or unallocated voxel centre is an obstacle too.
// A sphere (c, R) is free when no obstacle centre lies within R of c, decided as:
//   c known:   d(v) - |c - centre(v)| > R (a lower bound of the true clearance: the ESDF is
//              1-Lipschitz), and under kOccupied no unknown voxel centre within R (scanned);
//   c unknown: kOccupied: never free; kFree: no site/inside voxel centre within R (scanned).
// Never free: non-finite input, negative R, and R >= max_distance_m (the ESDF holds no larger
// clearance; this also bounds the scans).
// Scans visit O((R / voxel)^3) voxels; the plain ESDF test is O(1).
// Segments are sampled every <= half a voxel (h); each sample is a sphere of radius
// sqrt(r^2 + (h/2)^2), which covers the capsule between samples. A path is free when all its
// segments are; a one-point path is a sphere; an empty path is free (nothing to check).
// Thread safety: every method is const and touches no shared mutable state: thread safe. The map
// must not change while a query runs.
#include <Eigen/Core>
#include <cstdint>
#include <vector>

#include "strata/map/esdf_layer.h"

namespace strata {

enum class EsdfStatus : std::uint32_t { kKnown = 0, kUnknown = 1, kOutside = 2 };

enum class UnknownPolicy : std::uint32_t {
  kOccupied = 0,  // safe default: unknown space may hold an obstacle
  kFree = 1,      // optimistic (exploration through unobserved space)
};

struct EsdfSample {
  float distance_m = 0.0f;
  Eigen::Vector3f gradient = Eigen::Vector3f::Zero();  // zero when not interpolable
  EsdfStatus status = EsdfStatus::kOutside;
  bool interpolated = false;  // all 8 neighbours known: distance and gradient trilinear
};

struct EsdfSegment {
  Eigen::Vector3f a_W;
  Eigen::Vector3f b_W;
};

class EsdfQuery {
 public:
  /// `map` must outlive the query and stay unchanged while queries run.
  explicit EsdfQuery(const EsdfMap& map);

  const EsdfMap& map() const { return map_; }
  float voxelSize() const { return map_.voxel_size_m; }

  /// Distance, gradient and status per point. Thread safe.
  std::vector<EsdfSample> sample(const std::vector<Eigen::Vector3f>& points_W) const;
  EsdfSample sample(const Eigen::Vector3f& p_W) const;
  /// Status of the voxel holding p (no interpolation). Thread safe.
  EsdfStatus status(const Eigen::Vector3f& p_W) const;

  /// One flag per centre (1 = free). Thread safe.
  std::vector<std::uint8_t> isSphereFree(const std::vector<Eigen::Vector3f>& centres_W,
                                         float radius_m, float margin_m,
                                         UnknownPolicy policy = UnknownPolicy::kOccupied) const;
  bool isSphereFree(const Eigen::Vector3f& centre_W, float radius_m, float margin_m,
                    UnknownPolicy policy = UnknownPolicy::kOccupied) const;

  /// Capsule of `radius_m` around each segment. Thread safe.
  std::vector<std::uint8_t> isSegmentFree(const std::vector<EsdfSegment>& segments, float radius_m,
                                          UnknownPolicy policy = UnknownPolicy::kOccupied) const;
  bool isSegmentFree(const Eigen::Vector3f& a_W, const Eigen::Vector3f& b_W, float radius_m,
                     UnknownPolicy policy = UnknownPolicy::kOccupied) const;
  /// Every segment of the polyline. Thread safe.
  bool isPathFree(const std::vector<Eigen::Vector3f>& polyline_W, float radius_m,
                  UnknownPolicy policy = UnknownPolicy::kOccupied) const;

 private:
  const EsdfMap& map_;
};

}  // namespace strata
