#pragma once
// Triangle meshes of the world's shapes. Every part is a closed, consistently wound mesh with
// outward normals (counter-clockwise seen from outside); composite shapes (chair, table, shelf) are
// several parts whose interiors are disjoint (they may touch), so "inside the shape" = inside any
// part.
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <vector>

#include "strata/mesh/mesh.h"
#include "strata/sim/world/world_spec.h"

namespace strata::sim {

/// Axis-aligned box [min_m, max_m]: 8 vertices, 12 triangles.
Mesh boxMesh(const Eigen::Vector3d& min_m, const Eigen::Vector3d& max_m);

/// Upright cylinder (axis +z through the origin) from z0 to z1, a prism of `segments` sides.
Mesh cylinderMesh(double radius_m, double z0_m, double z1_m, int segments);

/// The closed parts of a shape in its own frame (footprint centred on the origin, bottom at z = 0).
/// For ShapeKind::kMesh, `loaded` is the normalised file mesh (see mesh_file.h), used as one part.
std::vector<Mesh> shapeParts(const ShapeSpec& shape, const Mesh* loaded = nullptr);

/// Appends `part`, moved by T_W_P and coloured `albedo` per vertex, to `out`.
void appendMesh(const Mesh& part, const Eigen::Isometry3d& T_W_P,
                const std::array<std::uint8_t, 3>& albedo, Mesh& out);

/// Pose of an object standing on the floor: footprint centre (x, y), yaw about +z in degrees.
Eigen::Isometry3d floorPose(const Eigen::Vector2d& at_m, double yaw_deg);

}  // namespace strata::sim
