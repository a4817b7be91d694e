#pragma once
// Closest point on a triangle (Ericson, Real-Time Collision Detection, 5.1.5), double precision.
#include <Eigen/Core>

namespace strata::sim {

/// The point of triangle (a, b, c) nearest to p. Degenerate triangles are handled (the result is
/// then on one of their edges).
Eigen::Vector3d closestPointOnTriangle(const Eigen::Vector3d& p, const Eigen::Vector3d& a,
                                       const Eigen::Vector3d& b, const Eigen::Vector3d& c);

}  // namespace strata::sim
