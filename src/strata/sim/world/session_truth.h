#pragma once
// Ground truth of one session of a world: where every object is, whether it is there, what changed,
// and the lighting.
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <string>
#include <vector>

#include "strata/sim/world/world_spec.h"

namespace strata::sim {

/// How an object differs from a reference session.
enum class Change {
  kNone,     // present in both at the same pose, or absent in both
  kMoved,    // present in both, pose differs
  kRemoved,  // present in the reference, absent now
  kAdded,    // absent in the reference, present now
};

const char* changeName(Change change);  // "none", "moved", "removed", "added"

struct ObjectState {
  int id = 0;  // 1..N, the same object in every session (0 is the static world)
  std::string name;
  ShapeKind shape = ShapeKind::kBox;
  bool present = false;
  /// Object frame (footprint centre on the floor, z up) to world. For an absent object: its last
  /// pose (or its first, if it was never present); meaningless for rendering.
  Eigen::Isometry3d T_W_O = Eigen::Isometry3d::Identity();
  Eigen::Vector2d at_m = Eigen::Vector2d::Zero();  // T_W_O as the generator drew it
  double yaw_deg = 0.0;
  Change since_previous = Change::kNone;  // session 0: kNone
  Change since_first = Change::kNone;     // relative to session 0
};

/// A directional light plus ambient, in the convention of sim/sensors/lighting.h: shading factor
/// = ambient + intensity * max(0, n . direction_W).
struct Light {
  Eigen::Vector3d direction_W = Eigen::Vector3d(0.3, -0.4, 1.0).normalized();  // towards the light
  double intensity = 0.65;
  double ambient = 0.35;
};

struct SessionTruth {
  int index = 0;
  std::vector<ObjectState> objects;  // every object of the world, objects[id - 1]
  Light light;

  /// Ids whose since_previous (or since_first) is not kNone, ascending.
  std::vector<int> changedIds(bool since_first = false) const;
  int presentCount() const;
};

}  // namespace strata::sim
