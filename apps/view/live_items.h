#pragma once
// strata-view's conversions of strata-mapper's messages into scene items: block meshes, object
// meshes, the ESDF slice as the page's image and distances read from it, map stats as the page's
// table. Every position is in the map's world frame W, metres.
//
// Errors: InputError for content no viewer should show (non-finite positions, triangle indices
// outside their vertices, a slice of non-positive resolution); the caller counts and skips it.
// Pure functions; thread safe.
#include <Eigen/Geometry>
#include <cstdint>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "strata/esdf_slice_t.hpp"
#include "strata/map_stats_t.hpp"
#include "strata/mesh/mesh.h"
#include "strata/mesh_block_t.hpp"
#include "view/scene_items.h"

namespace strata::view {

/// The scene id of a map block: "block:x,y,z" (integer block coordinates).
std::string blockId(const std::int32_t index[3]);

/// A mesh block's surface with its colours.
Mesh blockMesh(const mesh_block_t& block);

/// A mesh from an LCM message's rows (vertices [n][3], triangles [t][3]), each vertex mapped by
/// `T` (the identity for meshes already in W). `what` names it in errors.
Mesh messageMesh(const std::vector<std::vector<float>>& vertices,
                 const std::vector<std::vector<std::int32_t>>& triangles, const char* what,
                 const Eigen::Isometry3d& T = Eigen::Isometry3d::Identity());

/// The axis-aligned box of a mesh's vertices (zero for an empty mesh).
void meshBounds(const Mesh& mesh, Eigen::Vector3f* min_W, Eigen::Vector3f* max_W);

/// The slice as the page draws it: NaN where a cell is not observed (esdf_slice_t.state != 2),
/// the origin moved from cell (0, 0)'s centre to its corner, the colour scale up to the largest
/// known distance.
EsdfSliceImage sliceImage(const esdf_slice_t& slice);

/// The distance at (x_m, y_m) on `slice`: bilinear between the four cell centres around the point
/// when all four are known, else the cell holding it; nullopt outside the slice or where that
/// cell is unknown.
std::optional<float> sliceDistance(const EsdfSliceImage& slice, float x_m, float y_m);

/// The page's stats table for a map_stats_t: "blocks" (map blocks on the mapper's device),
/// "frames" (fused), "frames received", "dropped", "rejected", "session", "session open",
/// "device MB", "fuse ms", "queue", "mapper bad messages".
nlohmann::json statsValues(const map_stats_t& stats);

}  // namespace strata::view
