#pragma once
// The static part of a world as closed parts in world coordinates: per room a floor slab, a ceiling
// slab and four walls (outside the interior rectangle, `wall_thickness` thick), walls split around
// doors, and the static elements (shelves, tables, pillars, ...). Parts may touch or overlap (rooms
// sharing a wall); each stays closed so "inside the static world" = inside any part.
#include <vector>

#include "strata/mesh/mesh.h"
#include "strata/sim/world/footprint.h"
#include "strata/sim/world/world_spec.h"

namespace strata::sim {

struct StaticPart {
  Mesh mesh;  // world frame
  Material material;
};

/// A shape's closed parts in its own frame, and the half extents of its footprint.
struct ShapeGeometry {
  std::vector<Mesh> parts;
  Eigen::Vector2d half_footprint_m = Eigen::Vector2d::Zero();
};

/// Loads the file of a mesh shape (filling shape.size_m) and builds the parts of any shape.
ShapeGeometry buildShapeGeometry(ShapeSpec& shape);

struct StaticWorld {
  std::vector<StaticPart> parts;
  std::vector<Footprint> obstacles;   // walls and static elements: objects are never placed here
  std::vector<Footprint> door_zones;  // in front of and behind every door: kept free
};

/// InputError "file:line: doors[i]: ..." for a door that lies in no wall.
StaticWorld buildStaticWorld(const WorldSpec& spec,
                             const std::vector<ShapeGeometry>& element_shapes);

}  // namespace strata::sim
