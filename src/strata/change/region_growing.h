#pragma once
// Mesh segmentation for object discovery: face adjacency, smooth regions grown over similar
// normals, and connected components of a face subset.
#include <cstddef>
#include <cstdint>
#include <vector>

#include "strata/mesh/mesh.h"

namespace strata::change {

/// Faces that share an edge, compressed rows: the neighbours of face f are
/// neighbours[offsets[f] .. offsets[f + 1]).
struct FaceAdjacency {
  std::vector<std::uint32_t> offsets;
  std::vector<std::uint32_t> neighbours;
};

/// O(F log F). Faces on a non-manifold edge are all neighbours of each other.
FaceAdjacency buildFaceAdjacency(const Mesh& mesh);

/// Faces partitioned into regions: region[f] in [0, count).
struct Regions {
  std::vector<std::uint32_t> region;
  std::size_t count = 0;
};

/// Breadth-first growth from the lowest unassigned face: a neighbour joins when its normal is
/// within `neighbour_angle_deg` of the face it is reached from and within `mean_angle_deg` of the
/// region's area-weighted mean normal. Zero-area faces join any region they touch.
Regions growSmoothRegions(const Mesh& mesh, const FaceAdjacency& adjacency,
                          float neighbour_angle_deg, float mean_angle_deg);

/// Gives every face its region's label: dynamic when more than `dynamic_share` of the region's
/// faces are dynamic.
std::vector<bool> labelRegions(const Regions& regions, const std::vector<bool>& face_dynamic,
                               float dynamic_share);

/// Edge-connected components of the faces with member[f]: component[f] in [0, count) for members,
/// -1 for the rest. Components are numbered in order of their lowest face.
struct Components {
  std::vector<int> component;
  std::size_t count = 0;
};
Components connectedComponents(const FaceAdjacency& adjacency, const std::vector<bool>& member);

/// Joins components that come within `gap_m` of each other (vertex to vertex): thin parts (chair
/// legs, shelf boards about a voxel thick) often lose their mesh connection to the rest of the
/// object. Keeps the numbering rule (order of the lowest face). gap_m <= 0 changes nothing.
Components mergeNearbyComponents(const Mesh& mesh, const Components& components, float gap_m);

}  // namespace strata::change
