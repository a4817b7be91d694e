#pragma once
// Per-block meshes (mesh/block_meshes.h) as mesh_block_t messages, and back.
#include <vector>

#include "strata/mesh/block_meshes.h"
#include "strata/mesh_block_t.hpp"

namespace strata::lcm_io {

/// One block's mesh as a message (positions, colours, triangles).
mesh_block_t toMessage(const BlockMesh& block);
/// The mesh of each of `blocks` as messages (meshBlocks, then toMessage).
std::vector<mesh_block_t> meshBlockMessages(const TsdfMap& map, const std::vector<BlockIndex>& blocks,
                                     const MeshOptions& options = {});
/// A block message as a Mesh (for viewers, tests).
Mesh toMesh(const mesh_block_t& block);

}  // namespace strata::lcm_io
