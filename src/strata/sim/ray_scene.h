#pragma once
// What a simulated sensor needs from a scene: batched ray casts that report distance, normal,
// object identity and material, plus exact signed distance and occupancy for ground truth.
// Implemented by the Embree world scene (sim/world/) and by adapters of analytic scenes for tests.
#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <limits>
#include <vector>

namespace strata::sim {

/// Surface appearance that the sensor models react to.
struct Material {
  std::array<std::uint8_t, 3> albedo{180, 180, 180};
  /// 0 = matte; near 1 = mirror-like: structured-light depth is lost there.
  float reflectivity = 0.0f;
};

inline constexpr std::int32_t kStaticObjectId = 0;   // walls, floor, fixed furniture
inline constexpr std::int32_t kNoHitObjectId = -1;   // the ray hit nothing

struct Ray {
  Eigen::Vector3f origin_W;
  Eigen::Vector3f direction_W;  // unit length
  float max_t_m = std::numeric_limits<float>::infinity();
};

struct RayHit {
  float t_m = std::numeric_limits<float>::infinity();  // infinity: no hit within max_t_m
  Eigen::Vector3f normal_W = Eigen::Vector3f::Zero();   // unit, facing the ray's origin
  std::int32_t object_id = kNoHitObjectId;              // movable objects are 1, 2, ...
  Material material;
  bool hit() const { return object_id != kNoHitObjectId; }
};

/// Thread safety: every const method may be called from several threads at once.
class RayScene {
 public:
  virtual ~RayScene() = default;
  /// Casts rays[i] into hits[i] (hits is resized). Implementations batch and parallelise.
  virtual void intersect(const std::vector<Ray>& rays, std::vector<RayHit>& hits) const = 0;
  /// Exact signed distance to the nearest surface (closest point on the meshes), negative inside
  /// solids.
  virtual float signedDistance(const Eigen::Vector3f& p_W) const = 0;
  /// True inside a solid.
  virtual bool occupied(const Eigen::Vector3f& p_W) const { return signedDistance(p_W) < 0.0f; }
};

}  // namespace strata::sim
