#include "strata/sim/world/internal/static_geometry.h"

#include <algorithm>

#include "strata/core/error.h"
#include "strata/sim/world/mesh_file.h"
#include "strata/sim/world/shape_mesh.h"

namespace strata::sim {
namespace {

constexpr double kEps = 1e-9;

struct WallBox {
  Eigen::Vector3d min_m, max_m;
  Material material;
};

bool sameBox(const WallBox& a, const WallBox& b) {
  return (a.min_m - b.min_m).cwiseAbs().maxCoeff() < kEps &&
         (a.max_m - b.max_m).cwiseAbs().maxCoeff() < kEps;
}

/// Four walls around the interior, the corners owned by the walls along x so none overlap.
void addRoomWalls(const RoomSpec& room, double t, std::vector<WallBox>& walls) {
  const double x0 = room.min_m.x(), y0 = room.min_m.y(), x1 = room.max_m.x(), y1 = room.max_m.y();
  const double h = room.height_m;
  const std::vector<std::pair<Eigen::Vector3d, Eigen::Vector3d>> boxes = {
      {{x0 - t, y0 - t, 0}, {x1 + t, y0, h}},  // south (-y), corners included
      {{x0 - t, y1, 0}, {x1 + t, y1 + t, h}},  // north (+y), corners included
      {{x0 - t, y0, 0}, {x0, y1, h}},          // west (-x)
      {{x1, y0, 0}, {x1 + t, y1, h}},          // east (+x)
  };
  for (const auto& [min_m, max_m] : boxes) {
    const WallBox wall{min_m, max_m, room.walls};
    // Rooms sharing a wall produce the same box twice: keep one.
    const auto same = [&](const WallBox& w) { return sameBox(w, wall); };
    if (std::none_of(walls.begin(), walls.end(), same)) walls.push_back(wall);
  }
}

bool holdsDoor(const WallBox& wall, const DoorSpec& door) {
  return wall.min_m.z() < kEps && door.at_m.x() >= wall.min_m.x() - kEps &&
         door.at_m.x() <= wall.max_m.x() + kEps && door.at_m.y() >= wall.min_m.y() - kEps &&
         door.at_m.y() <= wall.max_m.y() + kEps;
}

int wallAxis(const WallBox& wall) {
  const Eigen::Vector3d size = wall.max_m - wall.min_m;
  return size.x() >= size.y() ? 0 : 1;
}

/// The wall minus the door opening: up to two side pieces and a lintel above the door.
std::vector<WallBox> cutDoor(const WallBox& wall, const DoorSpec& door) {
  const int axis = wallAxis(wall);
  const double lo = door.at_m[axis] - door.width_m / 2, hi = door.at_m[axis] + door.width_m / 2;
  std::vector<WallBox> pieces;
  if (lo > wall.min_m[axis] + kEps) {
    pieces.push_back(wall);
    pieces.back().max_m[axis] = lo;
  }
  if (hi < wall.max_m[axis] - kEps) {
    pieces.push_back(wall);
    pieces.back().min_m[axis] = hi;
  }
  if (door.height_m < wall.max_m.z() - kEps) {
    WallBox lintel = wall;
    lintel.min_m[axis] = std::max(lo, wall.min_m[axis]);
    lintel.max_m[axis] = std::min(hi, wall.max_m[axis]);
    lintel.min_m.z() = door.height_m;
    pieces.push_back(lintel);
  }
  return pieces;
}

/// Keep-out rectangle across the wall: the door's width, the wall plus `clearance` on each side.
Footprint doorZone(const WallBox& wall, const DoorSpec& door, double clearance_m) {
  const int axis = wallAxis(wall), across = 1 - axis;
  Footprint zone;
  zone.centre_m[axis] = door.at_m[axis];
  zone.centre_m[across] = 0.5 * (wall.min_m[across] + wall.max_m[across]);
  zone.half_m[axis] = door.width_m / 2;
  zone.half_m[across] = 0.5 * (wall.max_m[across] - wall.min_m[across]) + clearance_m;
  return zone;
}

void cutDoors(const WorldSpec& spec, std::vector<WallBox>& walls, StaticWorld& world) {
  for (std::size_t d = 0; d < spec.doors.size(); ++d) {
    const DoorSpec& door = spec.doors[d];
    std::vector<WallBox> next;
    bool used = false;
    for (const WallBox& wall : walls) {
      if (!holdsDoor(wall, door)) {
        next.push_back(wall);
        continue;
      }
      if (!used) world.door_zones.push_back(doorZone(wall, door, spec.door_clearance_m));
      used = true;
      const std::vector<WallBox> pieces = cutDoor(wall, door);
      next.insert(next.end(), pieces.begin(), pieces.end());
    }
    if (!used) {
      throw InputError(spec.source + ":" + std::to_string(door.line) + ": doors[" +
                       std::to_string(d) + "].at: lies in no wall (put it on a wall's line)");
    }
    walls = std::move(next);
  }
}

void addRoomSlabs(const RoomSpec& room, double t, StaticWorld& world) {
  const Eigen::Vector3d lo(room.min_m.x() - t, room.min_m.y() - t, 0.0);
  const Eigen::Vector3d hi(room.max_m.x() + t, room.max_m.y() + t, 0.0);
  world.parts.push_back({boxMesh(lo - Eigen::Vector3d(0, 0, t), hi), room.floor});
  world.parts.push_back({boxMesh(lo + Eigen::Vector3d(0, 0, room.height_m),
                                 hi + Eigen::Vector3d(0, 0, room.height_m + t)),
                         room.ceiling});
}

void addElements(const WorldSpec& spec, const std::vector<ShapeGeometry>& shapes,
                 StaticWorld& world) {
  for (std::size_t i = 0; i < spec.static_elements.size(); ++i) {
    const ObjectSpec& element = spec.static_elements[i];
    const Eigen::Isometry3d T_W_O = floorPose(*element.at_m, element.yaw_deg);
    for (const Mesh& part : shapes[i].parts) {
      StaticPart placed{Mesh{}, element.material};
      appendMesh(part, T_W_O, element.material.albedo, placed.mesh);
      placed.mesh.colors.clear();
      world.parts.push_back(std::move(placed));
    }
    world.obstacles.push_back(
        makeFootprint(shapes[i].half_footprint_m, *element.at_m, element.yaw_deg));
  }
}

}  // namespace

ShapeGeometry buildShapeGeometry(ShapeSpec& shape) {
  ShapeGeometry geometry;
  if (shape.kind == ShapeKind::kMesh) {
    const Mesh loaded = loadShapeMesh(shape);
    geometry.parts = shapeParts(shape, &loaded);
  } else {
    geometry.parts = shapeParts(shape);
  }
  geometry.half_footprint_m = 0.5 * shape.size_m.head<2>();
  return geometry;
}

StaticWorld buildStaticWorld(const WorldSpec& spec, const std::vector<ShapeGeometry>& shapes) {
  StaticWorld world;
  std::vector<WallBox> walls;
  for (const RoomSpec& room : spec.rooms) {
    addRoomSlabs(room, spec.wall_thickness_m, world);
    addRoomWalls(room, spec.wall_thickness_m, walls);
  }
  cutDoors(spec, walls, world);
  for (const WallBox& wall : walls) {
    world.parts.push_back({boxMesh(wall.min_m, wall.max_m), wall.material});
    world.obstacles.push_back(makeFootprint(0.5 * (wall.max_m - wall.min_m).head<2>(),
                                            0.5 * (wall.max_m + wall.min_m).head<2>(), 0.0));
  }
  addElements(spec, shapes, world);
  return world;
}

}  // namespace strata::sim
