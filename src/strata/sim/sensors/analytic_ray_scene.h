#pragma once
// RayScene over exact primitives (planes, boxes, spheres): the sensors' ground truth in tests.
// NOTE: built on sim/primitives.h rather than wrapping AnalyticScene, because analytic_scene.h and
// ray_scene.h both define strata::sim::RayHit and cannot meet in one translation unit, and because
// the sensors need per-primitive object ids and materials that AnalyticScene does not report.
#include <cstdint>
#include <vector>

#include "strata/sim/primitives.h"
#include "strata/sim/ray_scene.h"

namespace strata::sim {

/// Thread safety: const methods may be called from several threads at once; add() may not.
class AnalyticRayScene : public RayScene {
 public:
  /// `threads` used by intersect() (0 = hardware concurrency).
  explicit AnalyticRayScene(int threads = 0) : threads_(threads) {}

  /// Adds a primitive and returns its object id: kStaticObjectId (0) for planes, otherwise the
  /// primitive's insertion index (counting every primitive) + 1. Throws InputError for a
  /// degenerate primitive. The material's albedo is the primitive's.
  std::int32_t add(Plane plane, float reflectivity = 0.0f);
  std::int32_t add(const Box& box, float reflectivity = 0.0f);
  std::int32_t add(const Sphere& sphere, float reflectivity = 0.0f);

  void intersect(const std::vector<Ray>& rays, std::vector<RayHit>& hits) const override;
  float signedDistance(const Eigen::Vector3f& p_W) const override;

  /// Closest hit of one ray in double precision (0 < t <= max_t); hit() is false on a miss.
  RayHit castRay(const Eigen::Vector3d& origin_W, const Eigen::Vector3d& unit_dir_W,
                 double max_t_m) const;
  double signedDistance(const Eigen::Vector3d& p_W) const;

 private:
  template <typename Primitive>
  struct Entry {
    Primitive primitive;
    std::int32_t object_id;
    Material material;
  };
  template <typename Primitive>
  std::int32_t addEntry(std::vector<Entry<Primitive>>& entries, const Primitive& primitive,
                        std::int32_t object_id, float reflectivity);

  int threads_ = 0;
  std::int32_t primitive_count_ = 0;
  std::vector<Entry<Plane>> planes_;
  std::vector<Entry<Box>> boxes_;
  std::vector<Entry<Sphere>> spheres_;
};

}  // namespace strata::sim
