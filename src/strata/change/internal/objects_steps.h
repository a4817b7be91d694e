#pragma once
// Internal to objects.cpp: the steps of object discovery that are not mesh segmentation.
#include <vector>

#include "strata/change/change_types.h"
#include "strata/change/object_discovery.h"
#include "strata/mesh/mesh.h"

namespace strata::change::detail {

/// Per vertex: the dynamic share of the trilinear weights of the 8 voxels around it is at least
/// `vote` (voxels outside allocated blocks count as not dynamic).
std::vector<bool> labelVertices(const Mesh& mesh, const LabelMap& labels, float vote);

/// Per face: at least two of its three vertices are dynamic.
std::vector<bool> labelFaces(const Mesh& mesh, const std::vector<bool>& vertex_dynamic);

/// The faces listed, with the vertices they use (renumbered in first-use order) and their normals
/// and colours.
Mesh subMesh(const Mesh& mesh, const std::vector<std::uint32_t>& faces);

/// Smallest over largest singular value of the centred vertex positions (0 for fewer than 3
/// vertices): near 0 for a flat piece, about 0.3 or more for a box seen from two sides.
float singularValueRatio(const Mesh& mesh);

/// Bounding box, centroid and count filled from the mesh.
DiscoveredObject makeObject(Mesh mesh, int session);

}  // namespace strata::change::detail
