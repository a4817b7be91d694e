#include "object_volume_scene.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace strata::test {

Eigen::AlignedBox3d footBox(double size_x_m, double size_y_m, double height_m) {
  return Eigen::AlignedBox3d(Eigen::Vector3d(-0.5 * size_x_m, -0.5 * size_y_m, -0.1),
                             Eigen::Vector3d(0.5 * size_x_m, 0.5 * size_y_m, height_m));
}

Sdf placed(const Sdf& sdf_L, const Eigen::Isometry3d& T_W_L) {
  const Eigen::Isometry3d T_L_W = T_W_L.inverse();
  return [sdf_L, T_L_W](const Eigen::Vector3d& p_W) { return sdf_L(T_L_W * p_W); };
}

Sdf placedBox(const Eigen::AlignedBox3d& box_L, const Eigen::Isometry3d& T_W_L) {
  return placed([box_L](const Eigen::Vector3d& p) { return boxSdf(p, box_L); }, T_W_L);
}

Sdf cylinderSdf(double radius_m, double height_m) {
  return [radius_m, height_m](const Eigen::Vector3d& p) {
    const double half = 0.5 * (height_m + 0.1), centre_z = 0.5 * (height_m - 0.1);
    const Eigen::Vector2d q(p.head<2>().norm() - radius_m, std::abs(p.z() - centre_z) - half);
    return std::min(q.maxCoeff(), 0.0) + q.cwiseMax(0.0).norm();
  };
}

Eigen::Isometry3d floorPose(double x_m, double y_m, double yaw_rad) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = Eigen::AngleAxisd(yaw_rad, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  T.translation() = Eigen::Vector3d(x_m, y_m, 0.0);
  return T;
}

ObjectSession makeObjectSession(const Sdf& object_W, const PointTest& observed, int session) {
  const auto scene = [&](const Eigen::Vector3d& p) { return std::min(p.z(), object_W(p)); };
  const auto seen = [&](const Eigen::Vector3d& p) {
    return p.x() > 0.05 && p.y() > 0.05 && p.x() < 1.55 && p.y() < 1.55 && observed(p);
  };
  ObjectSession out;
  out.map = makeSdfMap(scene, {0, 0, -0.1}, {1.6, 1.6, 0.75}, kVoxel, seen);
  const change::LabelMap labels =
      makeLabels(out.map, [&](const Eigen::Vector3d& p) { return object_W(p) < 3 * kVoxel; });
  out.objects = change::extractObjects(out.map, labels, change::ObjectConfig{}, session, nullptr,
                                       &out.surface);
  return out;
}

const change::DiscoveredObject& onlyObject(const ObjectSession& session) {
  if (session.objects.size() != 1) {
    throw std::runtime_error("expected one discovered object, found " +
                             std::to_string(session.objects.size()));
  }
  return session.objects[0];
}

}  // namespace strata::test
