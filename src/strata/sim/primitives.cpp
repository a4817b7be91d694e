#include "strata/sim/primitives.h"

#include <cmath>
#include <limits>

namespace strata::sim {
namespace {

std::optional<SurfaceHit> hitIfInRange(double t_m, double max_t_m,
                                       const Eigen::Vector3d& normal_W) {
  if (!(t_m > 0.0) || t_m > max_t_m) return std::nullopt;
  return SurfaceHit{t_m, normal_W};
}

/// Entry into the slab |x| <= half along one axis: updates the latest entry (and its axis) and the
/// earliest exit. Returns false when the ray misses the slab entirely.
bool clipSlab(double origin, double dir, double half, int axis, double* t_enter, int* enter_axis,
              double* t_exit) {
  if (dir == 0.0) return std::abs(origin) <= half;
  const double t_a = (-half - origin) / dir;
  const double t_b = (half - origin) / dir;
  const double t_near = std::min(t_a, t_b);
  if (t_near > *t_enter) {
    *t_enter = t_near;
    *enter_axis = axis;
  }
  *t_exit = std::min(*t_exit, std::max(t_a, t_b));
  return true;
}

}  // namespace

double signedDistance(const Plane& plane, const Eigen::Vector3d& p_W) {
  return plane.normal_W.dot(p_W - plane.point_W);
}

double signedDistance(const Box& box, const Eigen::Vector3d& p_W) {
  const Eigen::Vector3d p_B = box.R_W_B.transpose() * (p_W - box.centre_W);
  const Eigen::Vector3d q = p_B.cwiseAbs() - box.half_extents_m;
  const double outside = q.cwiseMax(0.0).norm();
  const double inside = std::min(q.maxCoeff(), 0.0);
  return outside + inside;
}

double signedDistance(const Sphere& sphere, const Eigen::Vector3d& p_W) {
  return (p_W - sphere.centre_W).norm() - sphere.radius_m;
}

std::optional<SurfaceHit> intersect(const Plane& plane, const Eigen::Vector3d& origin_W,
                                    const Eigen::Vector3d& unit_dir_W, double max_t_m) {
  const double height = signedDistance(plane, origin_W);
  const double approach = plane.normal_W.dot(unit_dir_W);
  if (height <= 0.0 || approach >= 0.0) return std::nullopt;
  return hitIfInRange(-height / approach, max_t_m, plane.normal_W);
}

std::optional<SurfaceHit> intersect(const Box& box, const Eigen::Vector3d& origin_W,
                                    const Eigen::Vector3d& unit_dir_W, double max_t_m) {
  const Eigen::Vector3d o_B = box.R_W_B.transpose() * (origin_W - box.centre_W);
  const Eigen::Vector3d d_B = box.R_W_B.transpose() * unit_dir_W;
  double t_enter = -std::numeric_limits<double>::infinity();
  double t_exit = std::numeric_limits<double>::infinity();
  int enter_axis = -1;
  for (int axis = 0; axis < 3; ++axis) {
    if (!clipSlab(o_B[axis], d_B[axis], box.half_extents_m[axis], axis, &t_enter, &enter_axis,
                  &t_exit)) {
      return std::nullopt;
    }
  }
  if (enter_axis < 0 || t_enter > t_exit) return std::nullopt;
  Eigen::Vector3d normal_B = Eigen::Vector3d::Zero();
  normal_B[enter_axis] = d_B[enter_axis] > 0.0 ? -1.0 : 1.0;
  return hitIfInRange(t_enter, max_t_m, box.R_W_B * normal_B);
}

std::optional<SurfaceHit> intersect(const Sphere& sphere, const Eigen::Vector3d& origin_W,
                                    const Eigen::Vector3d& unit_dir_W, double max_t_m) {
  // |o + t d - c|^2 = r^2 with |d| = 1: t = -b -+ sqrt(b^2 - c).
  const Eigen::Vector3d oc = origin_W - sphere.centre_W;
  const double b = oc.dot(unit_dir_W);
  const double c = oc.squaredNorm() - sphere.radius_m * sphere.radius_m;
  if (c <= 0.0) return std::nullopt;  // origin inside or on the sphere
  // NOTE: discriminant from the perpendicular distance, which is accurate even for grazing rays.
  const Eigen::Vector3d closest = oc - b * unit_dir_W;
  const double discriminant = sphere.radius_m * sphere.radius_m - closest.squaredNorm();
  if (b >= 0.0 || discriminant < 0.0) return std::nullopt;
  const double t = -b - std::sqrt(discriminant);
  const Eigen::Vector3d normal_W = (oc + t * unit_dir_W) / sphere.radius_m;
  return hitIfInRange(t, max_t_m, normal_W.normalized());
}

}  // namespace strata::sim
