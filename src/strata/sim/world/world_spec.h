#pragma once
// What a world file says, after parsing and validation (world_parser.h reads it). Plain data: the
// static geometry, the layout generator and the Embree scene are built from it.
// Units: metres, degrees for yaw, 0-255 for albedo. The floor of every room is the plane z = 0 and
// z points up; yaw turns about +z, counter-clockwise seen from above.
#include <Eigen/Core>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "strata/sim/ray_scene.h"

namespace strata::sim {

/// kBox .. kMesh: primitives and mesh files. kVase .. kStool: procedural shapes
/// (procedural_shapes.h), generated deterministically from the shape's seed and the world's.
enum class ShapeKind { kBox, kCylinder, kChair, kTable, kShelf, kMesh, kVase, kBlob, kTube, kLShape,
                       kUShape, kStool };

/// Name used in files and ground truth ("box", "cylinder", ...).
const char* shapeKindName(ShapeKind kind);

/// A shape in its own frame: x/y centred on the footprint, z = 0 on the floor, +z up.
struct ShapeSpec {
  ShapeKind kind = ShapeKind::kBox;
  /// Overall extent (x, y, z) for box, chair, table, shelf; for mesh, the scaled bounding box
  /// (filled in when the mesh is loaded).
  Eigen::Vector3d size_m = Eigen::Vector3d(0.5, 0.5, 0.5);
  double radius_m = 0.25;  // cylinder
  int segments = 32;       // cylinder: sides of the polygonal approximation
  int levels = 4;          // shelf: boards, bottom and top included
  std::string mesh_path;   // mesh: as resolved (world file's folder, or data: prefix)
  double scale = 1.0;      // mesh: uniform factor applied to the file's coordinates
  bool y_up = false;       // mesh: the file's up axis is +y (most OBJ/PLY exports), not +z
  /// vase, blob, tube: the file's `seed`; World mixes the world's seed into it before the shape is
  /// built (so another world seed gives other shapes), and the mixed value is what stays here.
  std::uint64_t seed = 1;
  double thickness_m = 0.0;  // l_shape, u_shape: arm thickness (0: a third of the smaller side)
  int legs = 3;              // stool: number of legs, 3 to 8
};

/// A thing with a shape, a material and a place on the floor.
struct ObjectSpec {
  std::string name;
  ShapeSpec shape;
  Material material;
  std::optional<Eigen::Vector2d> at_m;  // footprint centre (x, y); absent: placed by the seed
  double yaw_deg = 0.0;
  bool optional = false;  // mesh: a missing file drops the object with a warning instead of failing
  int line = 0;           // 1-based line in the world file, for messages about this object
};

/// A door: an opening from the floor to height_m, width_m wide, in every wall that the point at_m
/// lies in (so one door joins two rooms whose walls touch or overlap).
struct DoorSpec {
  Eigen::Vector2d at_m = Eigen::Vector2d::Zero();
  double width_m = 0.9;
  double height_m = 2.0;
  int line = 0;
};

/// A room: interior floor rectangle [min_m, max_m] (x, y), walls outside it.
/// Limits of a world file, checked as it is parsed, before any geometry or grid is built: a room
/// (and so the world's maps, truth grids and paths) stays within sizes the simulator, the maps and
/// the exploration truth can hold (a 200 m room at a 5 cm voxel is 3.2e7 cells per metre of
/// height). The shipped worlds are at most 40 m across and 6 m high.
inline constexpr double kMaxRoomSideM = 200.0;
inline constexpr double kMaxRoomHeightM = 50.0;
/// Every coordinate of a room's corners and an object's position, metres from the origin.
inline constexpr double kMaxWorldCoordinateM = 1000.0;

struct RoomSpec {
  std::string name;
  Eigen::Vector2d min_m = Eigen::Vector2d::Zero();
  Eigen::Vector2d max_m = Eigen::Vector2d::Ones();
  double height_m = 2.5;
  Material floor, walls, ceiling;
};

/// Axis-aligned rectangle on the floor.
struct RegionSpec {
  Eigen::Vector2d min_m = Eigen::Vector2d::Zero();
  Eigen::Vector2d max_m = Eigen::Vector2d::Ones();
};

/// How the objects change from one session to the next.
struct ChangeRules {
  double move_probability = 0.25;   // per present object
  double remove_probability = 0.1;  // per present object
  int add_min = 0;                  // absent objects (pool or removed) brought in
  int add_max = 1;
  int min_changes = 1;               // at least this many changes per session
  double min_move_distance_m = 0.3;  // a move displaces the footprint centre at least this far
};

/// Rules for one later session, replacing the defaults there.
struct SessionOverride {
  int session = 1;
  ChangeRules rules;
};

struct LightingSpec {
  Eigen::Vector3d direction_W = Eigen::Vector3d(0.3, -0.4, 1.0);  // from surfaces towards the light
  double intensity = 0.65;
  double ambient = 0.35;
  double vary_direction_deg = 0.0;  // per later session: random tilt up to this angle
  double vary_intensity = 0.0;      // per later session: intensity * (1 + uniform(-v, v))
};

struct WorldSpec {
  std::string name;
  std::string source;  // file name used in messages
  std::uint64_t seed = 1;
  int session_count = 5;
  double wall_thickness_m = 0.1;
  std::vector<RoomSpec> rooms;
  std::vector<DoorSpec> doors;
  std::vector<ObjectSpec> static_elements;
  std::vector<ObjectSpec> objects;  // present in session 0
  std::vector<ObjectSpec> pool;     // absent in session 0, may appear later
  ChangeRules changes;
  std::vector<SessionOverride> overrides;
  std::vector<RegionSpec> regions;  // empty: every room's interior
  double clearance_m = 0.1;         // free gap kept around every placed footprint
  double door_clearance_m = 0.6;    // kept free on both sides of a door
  LightingSpec lighting;
};

}  // namespace strata::sim
