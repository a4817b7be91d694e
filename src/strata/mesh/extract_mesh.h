#pragma once
// Marching cubes over the allocated blocks of a host TSDF map.
//
// Cubes join 8 neighbouring voxel centres, across block borders too. A cube emits nothing when a
// corner is unobserved (weight < min_weight) or when it straddles a truncation discontinuity (see
// max_crossing_jump_truncations). Vertices lie on cube edges (linear interpolation of tsdf and
// colour) and are welded: one vertex per global voxel edge. Triangles face free space (tsdf > 0).
// NOTE: tsdf == 0 counts as positive. Where a voxel's tsdf is exactly 0 the vertices of its edges
// coincide in position (zero-area triangles); they stay distinct, so the mesh stays index-manifold.
#include "strata/map/tsdf_map.h"
#include "strata/mesh/mesh.h"

namespace strata {

struct MeshOptions {
  /// Voxels with a weight below this count as unobserved and produce no surface. Higher hides
  /// surfaces seen only once or at the fading end of the weight drop-off.
  float min_weight = 1e-3f;
  /// Per-vertex normals from the TSDF gradient (central differences at the two voxels of the
  /// vertex's edge, interpolated like the position). Cheap (under 10 % of the meshing time).
  bool compute_normals = true;
  /// A cube is skipped when a sign change along one of its edges jumps by more than this many
  /// truncation distances. A real surface changes the tsdf by at most about one voxel per voxel
  /// step (a distance field is 1-Lipschitz; more at grazing views), while the seam where the band's
  /// +trunc side meets a -trunc side (behind thin objects, band edges) jumps by about 2
  /// truncations. NOTE: with truncation below ~2 voxels the two overlap; raise this to keep grazing
  /// surfaces.
  float max_crossing_jump_truncations = 1.0f;
  /// Worker threads over blocks; 0 = std::thread::hardware_concurrency(). The output is the same
  /// for any count: blocks are meshed in TsdfMap::sortedBlockIndices() order.
  int num_threads = 0;

  /// Throws InputError naming the bad field.
  void validate() const;
};

/// Thread safe for concurrent calls on an unchanging map.
Mesh extractMesh(const TsdfMap& map, const MeshOptions& options = {});

}  // namespace strata
