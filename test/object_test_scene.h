#pragma once
// Sessions for the object-database tests, built from analytic maps (change_test_scene.h): things
// standing on a floor, each partially observed, labelled dynamic around them, and their objects
// discovered by change::extractObjects.
#include <Eigen/Geometry>
#include <vector>

#include "strata/change/object_discovery.h"
#include "change_test_scene.h"
#include "strata/objects/object_database.h"

namespace strata::test {

/// A thing on the floor: its signed distance in its own frame P (footprint at the origin, bottom
/// at z = 0, sunk 0.1 m into the floor so it joins it), where it stands, and which of its sides
/// the session observed (in P; the floor around it stays observed).
struct Thing {
  Sdf sdf_P;
  Eigen::Vector2d at_m = Eigen::Vector2d::Zero();
  double yaw_deg = 0.0;
  PointTest observed_P = [](const Eigen::Vector3d&) { return true; };

  Eigen::Isometry3d T_W_P() const;
  double sdfW(const Eigen::Vector3d& p_W) const;
};

/// The L: a long low wall with a shorter wing at one end (no symmetry under yaw).
double lShapeSdf(const Eigen::Vector3d& p_P);
/// A box of about the L's size: the prefilter lets it through, the rest must tell them apart.
double boxShapeSdf(const Eigen::Vector3d& p_P);

struct Session {
  TsdfMap map{MapConfig{}};
  change::LabelledSurface surface;
  std::vector<change::DiscoveredObject> segments;
};

/// A 2 x 2 m session (2 cm voxels) with a floor and `things`, and its discovered objects.
Session makeSession(const std::vector<Thing>& things, int session);

// Session 1: the L, its wing side unobserved. Session 2: the L turned 70 deg, only its front
// half observed, and the box. Session 3: the L turned 200 deg, seen from behind (its
// front unobserved).
extern const Thing kL1, kL2, kL3, kBox;

struct Fixture {
  objects::ObjectDatabase database;
  std::vector<std::vector<objects::SegmentOutcome>> outcomes;
};

/// Sessions 1, 2, 3 added to a default database once per process.
const Fixture& threeSessions();

}  // namespace strata::test
