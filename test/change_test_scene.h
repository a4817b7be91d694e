#pragma once
// Constructed inputs for the object-discovery and evaluation tests: TSDF maps and label layers
// filled from analytic signed distance functions, and box meshes.
#include <Eigen/Geometry>
#include <functional>

#include "strata/change/change_types.h"
#include "strata/map/tsdf_map.h"
#include "strata/mesh/mesh.h"

namespace strata::test {

using Sdf = std::function<double(const Eigen::Vector3d&)>;
using PointTest = std::function<bool(const Eigen::Vector3d&)>;

/// Exact signed distance to an axis-aligned box (negative inside).
double boxSdf(const Eigen::Vector3d& p, const Eigen::AlignedBox3d& box);

/// Every voxel of the blocks covering [lo, hi]: truncated `sdf`, weight 20 where `observed` and
/// in front of or within the band (free space observed, as with free-space allocation), 0
/// elsewhere; grey colour.
TsdfMap makeSdfMap(const Sdf& sdf, const Eigen::Vector3d& lo, const Eigen::Vector3d& hi,
                   float voxel_size_m, const PointTest& observed);

/// Labels over the map's blocks: dynamic where `dynamic` holds at the voxel centre, else static.
change::LabelMap makeLabels(const TsdfMap& map, const PointTest& dynamic);

/// Closed mesh of a box (12 triangles, outward normals).
Mesh boxMesh(const Eigen::AlignedBox3d& box);

/// A session's map and dynamic part for object discovery, 2 cm voxels over 2 x 2 m: a floor, two
/// moved boxes (A larger than B), a pebble too small to keep, a flat free-standing poster labelled
/// dynamic (planar: dropped), and a floor patch labelled dynamic (label noise).
inline constexpr float kVoxel = 0.02f;
inline const Eigen::AlignedBox3d kBoxA(Eigen::Vector3d(0.5, 0.5, -0.1),
                                       Eigen::Vector3d(0.9, 0.8, 0.4));
inline const Eigen::AlignedBox3d kBoxB(Eigen::Vector3d(1.3, 1.2, -0.1),
                                       Eigen::Vector3d(1.6, 1.5, 0.3));
struct ObjectsScene {
  TsdfMap map;
  change::LabelMap labels;
};
ObjectsScene makeObjectsScene();

}  // namespace strata::test
