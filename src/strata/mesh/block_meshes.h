#pragma once
// Per-block meshes for streaming (the LCM mapper's mesh_update_t, Mapper::meshChangedBlocks): the
// marching-cubes surface of the cubes whose lower corner
// lies in a block, made self-contained (vertices it borrows from + neighbours are copied in), so a
// viewer replaces a block's mesh without knowing the others. The union over all blocks is
// extractMesh's mesh (same BlockMesher, same vertices; shared ones duplicated per block).
#include <vector>

#include "strata/map/tsdf_map.h"
#include "strata/mesh/extract_mesh.h"
#include "strata/mesh/mesh.h"

namespace strata {

/// The surface of one block, self-contained (positions and colours; no normals).
struct BlockMesh {
  BlockIndex index;
  Mesh mesh;  // empty when the block holds no surface
};

/// Allocated blocks whose mesh may change when the voxels of `changed` change: the changed blocks
/// and their 26 neighbours (cubes reach one voxel into + neighbours, gradients one more, and the
/// vertex test of a block reads a one-voxel halo on the - side). Sorted (z, y, x), unique.
std::vector<BlockIndex> blocksToRemesh(const TsdfMap& map, const std::vector<BlockIndex>& changed);

/// The mesh of each of `blocks` (allocated blocks of `map`), in the given order.
/// Thread safe for concurrent calls on distinct or unchanging maps.
std::vector<BlockMesh> meshBlocks(const TsdfMap& map, const std::vector<BlockIndex>& blocks,
                                  const MeshOptions& options = {});

}  // namespace strata
