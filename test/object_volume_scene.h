#pragma once
// Sessions for the object-volume tests: a floor at z = 0 with one object standing on it, filled
// from analytic signed distances (change_test_scene.h), its object discovered by
// change::extractObjects.
#include <Eigen/Geometry>

#include "strata/change/object_discovery.h"
#include "change_test_scene.h"
#include "strata/objects/object_observation.h"

namespace strata::test {

/// A box in its own frame L: footprint centred on the origin, from 10 cm under the floor up to
/// `height_m`.
Eigen::AlignedBox3d footBox(double size_x_m, double size_y_m, double height_m);

/// Signed distance of an object given in its frame L, placed at T_W_L.
Sdf placed(const Sdf& sdf_L, const Eigen::Isometry3d& T_W_L);

/// Signed distance of `box_L` placed at T_W_L.
Sdf placedBox(const Eigen::AlignedBox3d& box_L, const Eigen::Isometry3d& T_W_L);

/// Signed distance of an upright cylinder in L (axis z, from 10 cm under the floor to height_m).
Sdf cylinderSdf(double radius_m, double height_m);

/// Yaw about z and a translation on the floor.
Eigen::Isometry3d floorPose(double x_m, double y_m, double yaw_rad);

struct ObjectSession {
  TsdfMap map{MapConfig{}};
  change::LabelledSurface surface;
  std::vector<change::DiscoveredObject> objects;
};

/// 1.6 x 1.6 m of floor with `object_W` on it, observed where `observed` holds (and 5 cm in from
/// the map's edges); the object labelled dynamic within 3 voxels.
ObjectSession makeObjectSession(const Sdf& object_W, const PointTest& observed, int session);

/// The session's one discovered object; throws std::runtime_error when it has none or several.
const change::DiscoveredObject& onlyObject(const ObjectSession& session);

}  // namespace strata::test
