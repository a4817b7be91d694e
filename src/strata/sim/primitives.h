#pragma once
// Solid primitives of the analytic scene: exact signed distance (negative inside) and exact ray
// intersection (the entry point of a ray that starts outside the solid). Double precision
// throughout so rendered depth and distances agree to ~1e-9 m.
#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <optional>

namespace strata::sim {

using Albedo = std::array<std::uint8_t, 3>;  // RGB

/// Half-space: the solid is everything behind the plane, {p : normal . (p - point) < 0}.
struct Plane {
  Eigen::Vector3d point_W = Eigen::Vector3d::Zero();
  Eigen::Vector3d normal_W = Eigen::Vector3d::UnitZ();  // unit (AnalyticScene::add normalises)
  Albedo albedo{128, 128, 128};
};

/// Oriented box: R_W_B rotates box-frame vectors into the world; |x_B| <= half_extents_m per axis.
struct Box {
  Eigen::Vector3d centre_W = Eigen::Vector3d::Zero();
  Eigen::Vector3d half_extents_m = Eigen::Vector3d::Constant(0.5);
  Eigen::Matrix3d R_W_B = Eigen::Matrix3d::Identity();
  Albedo albedo{128, 128, 128};
};

struct Sphere {
  Eigen::Vector3d centre_W = Eigen::Vector3d::Zero();
  double radius_m = 0.5;
  Albedo albedo{128, 128, 128};
};

/// A ray's first entry into a solid: distance along the unit direction and the outward unit normal.
struct SurfaceHit {
  double t_m = 0.0;
  Eigen::Vector3d normal_W = Eigen::Vector3d::UnitZ();
};

/// Exact signed distance to the primitive's surface, negative inside.
double signedDistance(const Plane& plane, const Eigen::Vector3d& p_W);
double signedDistance(const Box& box, const Eigen::Vector3d& p_W);
double signedDistance(const Sphere& sphere, const Eigen::Vector3d& p_W);

/// First entry of the ray origin + t * unit_dir with 0 < t <= max_t into the solid; nullopt when
/// there is none (also when the origin is inside the solid: rays only see solids from outside).
std::optional<SurfaceHit> intersect(const Plane& plane, const Eigen::Vector3d& origin_W,
                                    const Eigen::Vector3d& unit_dir_W, double max_t_m);
std::optional<SurfaceHit> intersect(const Box& box, const Eigen::Vector3d& origin_W,
                                    const Eigen::Vector3d& unit_dir_W, double max_t_m);
std::optional<SurfaceHit> intersect(const Sphere& sphere, const Eigen::Vector3d& origin_W,
                                    const Eigen::Vector3d& unit_dir_W, double max_t_m);

}  // namespace strata::sim
