#pragma once
// A scene of solid primitives (half-spaces, oriented boxes, spheres) with exact signed distance and
// exact depth rendering: the ground truth that TSDF/ESDF tests and benchmarks compare against.
//
// What is exact (union of solids, SDF = min of the solids' SDFs):
// - Outside every solid the min is the exact Euclidean distance to the union, whatever the layout.
// - The zero set is exactly the union's surface and the sign is always right.
// - Inside, the min is exact where a point's nearest boundary point on its solid is not covered by
//   another solid. With solids whose interiors are disjoint (they may touch, like a box resting on
//   the floor half-space) this fails only near contact faces, where |SDF| underestimates the depth.
//   makeDefaultScene() keeps interiors disjoint.
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <vector>

#include "strata/core/types.h"
#include "strata/sim/primitives.h"

namespace strata::sim {

struct AnalyticHit {
  double t_m = 0.0;                                     // along the unit direction
  Eigen::Vector3d normal_W = Eigen::Vector3d::UnitZ();  // outward, unit
  Albedo albedo{0, 0, 0};
};

/// Thread safety: const methods may be called from several threads at once.
class AnalyticScene {
 public:
  /// Throw InputError for a degenerate primitive (zero normal, non-positive size, non-rotation).
  void add(Plane plane);
  void add(const Box& box);
  void add(const Sphere& sphere);

  /// Exact signed distance to the union (see the header note), metres, negative inside.
  /// +infinity for an empty scene.
  double signedDistance(const Eigen::Vector3d& p_W) const;
  float signedDistance(const Eigen::Vector3f& p_W) const;

  /// First surface hit along origin + t * unit_dir with 0 < t <= max_t. Solids that contain the
  /// origin are not seen. `hit` may be null.
  bool castRay(const Eigen::Vector3d& origin_W, const Eigen::Vector3d& unit_dir_W, double max_t_m,
               AnalyticHit* hit) const;

  /// Depth = camera-frame z of the first hit along each pixel-centre ray (pixel (u, v) looks along
  /// ((u - cx) / fx, (v - cy) / fy, 1)), 0 on a miss or beyond max_depth_m.
  DepthImage renderDepth(const CameraIntrinsics& intrinsics, const Eigen::Isometry3d& T_W_C,
                         float max_depth_m) const;
  /// Albedo with Lambert shading under a fixed directional light plus ambient; black on a miss.
  ColorImage renderColor(const CameraIntrinsics& intrinsics, const Eigen::Isometry3d& T_W_C,
                         float max_depth_m) const;
  /// Both at once (one ray per pixel); either output may be null.
  void render(const CameraIntrinsics& intrinsics, const Eigen::Isometry3d& T_W_C, float max_depth_m,
              DepthImage* depth, ColorImage* color) const;

  std::size_t primitiveCount() const { return planes_.size() + boxes_.size() + spheres_.size(); }

 private:
  std::vector<Plane> planes_;
  std::vector<Box> boxes_;
  std::vector<Sphere> spheres_;
};

}  // namespace strata::sim
