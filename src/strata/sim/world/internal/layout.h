#pragma once
// The object layout of every session, drawn from the world's seed: session 0 places the `objects`
// (at their given poses, the rest at random), each later session moves, removes and adds objects
// by the change rules, with at least `min_changes` changes. Placement keeps every footprint inside
// a placement region, `clearance` away from other objects, walls and static elements, and off the
// door zones. Deterministic: the same spec and seed give bit-identical layouts on any machine.
#include <vector>

#include "strata/sim/world/footprint.h"
#include "strata/sim/world/world_spec.h"

namespace strata::sim {

struct Placement {
  bool present = false;
  Eigen::Vector2d at_m = Eigen::Vector2d::Zero();
  double yaw_deg = 0.0;
};

/// placements[object index] (index = id - 1: spec.objects, then spec.pool).
using Layout = std::vector<Placement>;

struct LayoutInput {
  const WorldSpec* spec = nullptr;
  std::vector<Eigen::Vector2d> half_footprints_m;  // per object index
  std::vector<Footprint> obstacles;                // static: walls, elements
  std::vector<Footprint> door_zones;
};

/// One layout per session. InputError naming the file and line of the object when session 0's
/// given poses overlap, or an object finds no free place, or a session can make no change.
std::vector<Layout> generateLayouts(const LayoutInput& input);

}  // namespace strata::sim
