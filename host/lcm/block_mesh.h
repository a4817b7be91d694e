#pragma once
// Per-block meshes for mesh_update_t: the marching-cubes surface of the cubes whose lower corner
// lies in a block, made self-contained (vertices it borrows from + neighbours are copied in), so a
// viewer replaces a block's mesh without knowing the others. The union over all blocks is
// extractMesh's mesh (same BlockMesher, same vertices; shared ones duplicated per block).
#include <vector>

#include "map/tsdf_map.h"
#include "mesh/extract_mesh.h"
#include "mesh/mesh.h"
#include "strata/mesh_block_t.hpp"

namespace strata::lcm_io {

/// Allocated blocks whose mesh may change when the voxels of `changed` change: the changed blocks
/// and their 26 neighbours (cubes reach one voxel into + neighbours, gradients one more, and the
/// vertex test of a block reads a one-voxel halo on the - side). Sorted (z, y, x), unique.
std::vector<BlockIndex> blocksToRemesh(const TsdfMap& map, const std::vector<BlockIndex>& changed);

/// The mesh of each of `blocks` (allocated blocks of `map`), in the given order.
std::vector<mesh_block_t> meshBlocks(const TsdfMap& map, const std::vector<BlockIndex>& blocks,
                                     const MeshOptions& options = {});

/// A block message as a Mesh (for viewers, tests).
Mesh toMesh(const mesh_block_t& block);

}  // namespace strata::lcm_io
