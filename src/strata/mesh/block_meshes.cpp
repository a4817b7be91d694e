#include "strata/mesh/block_meshes.h"

#include <algorithm>
#include <map>
#include <unordered_map>
#include <unordered_set>

#include "strata/mesh/internal/block_mesher.h"
#include "strata/core/parallel_for.h"

namespace strata {
namespace {

using detail::BlockMeshPart;

// Blocks per claimed chunk: enough to amortise a chunk's cache, few enough to balance.
constexpr std::size_t kMeshBlocksPerChunk = 64;

/// Meshes each block once per update, also the + neighbours whose vertices others borrow.
class PartCache {
 public:
  PartCache(const TsdfMap& map, const MeshOptions& options) : map_(map), mesher_(map, options) {}
  const BlockMeshPart* get(const BlockIndex& block) {
    const auto it = parts_.find(block);
    if (it != parts_.end()) return &it->second;
    if (map_.findBlock(block) == nullptr) return nullptr;
    return &parts_.emplace(block, mesher_.mesh(block)).first->second;
  }

 private:
  const TsdfMap& map_;
  detail::BlockMesher mesher_;
  std::unordered_map<BlockIndex, BlockMeshPart, BlockIndexHash> parts_;
};

void appendVertex(const BlockMeshPart& part, std::size_t i, Mesh& out) {
  out.vertices.push_back(part.vertices[i]);
  out.colors.push_back(part.colors[i]);
}

/// Index in `out` of the vertex an external reference names, copied in on first use; -1 when the
/// neighbour lacks it (cannot happen for a consistent map; the triangle is then skipped).
int borrowVertex(const BlockIndex& block, std::uint32_t ref, PartCache& cache,
                 std::map<std::uint32_t, int>& borrowed, Mesh& out) {
  const auto found = borrowed.find(ref);
  if (found != borrowed.end()) return found->second;
  const std::uint32_t code = (ref >> 11) & 7u;
  const auto slot = static_cast<std::uint16_t>(ref & 0x7FFu);
  const BlockMeshPart* neighbour =
      cache.get(block + Eigen::Vector3i(code & 1u, (code >> 1) & 1u, (code >> 2) & 1u));
  if (neighbour == nullptr) return -1;
  const auto& slots = neighbour->vertex_slots;
  const auto it = std::lower_bound(slots.begin(), slots.end(), slot);
  if (it == slots.end() || *it != slot) return -1;
  appendVertex(*neighbour, static_cast<std::size_t>(it - slots.begin()), out);
  const int index = static_cast<int>(out.vertices.size()) - 1;
  borrowed[ref] = index;
  return index;
}

BlockMesh meshOne(const BlockIndex& block, PartCache& cache) {
  BlockMesh result;
  result.index = block;
  Mesh& out = result.mesh;
  const BlockMeshPart* part = cache.get(block);
  if (part != nullptr) {
    for (std::size_t i = 0; i < part->vertices.size(); ++i) appendVertex(*part, i, out);
    std::map<std::uint32_t, int> borrowed;
    for (const auto& refs : part->triangles) {
      Eigen::Vector3i triangle;
      bool complete = true;
      for (int k = 0; k < 3; ++k) {
        const std::uint32_t ref = refs[k];
        triangle[k] = (ref & detail::kExternalVertex)
                          ? borrowVertex(block, ref, cache, borrowed, out)
                          : static_cast<std::int32_t>(ref);
        complete = complete && triangle[k] >= 0;
      }
      if (complete) out.triangles.push_back(triangle);
    }
  }
  return result;
}

bool sortedBefore(const BlockIndex& a, const BlockIndex& b) {
  if (a.z() != b.z()) return a.z() < b.z();
  if (a.y() != b.y()) return a.y() < b.y();
  return a.x() < b.x();
}

}  // namespace

std::vector<BlockIndex> blocksToRemesh(const TsdfMap& map, const std::vector<BlockIndex>& changed) {
  std::unordered_set<BlockIndex, BlockIndexHash> blocks;
  for (const BlockIndex& b : changed) {
    for (int dz = -1; dz <= 1; ++dz) {
      for (int dy = -1; dy <= 1; ++dy) {
        for (int dx = -1; dx <= 1; ++dx) {
          const BlockIndex n = b + BlockIndex(dx, dy, dz);
          if (map.findBlock(n) != nullptr) blocks.insert(n);
        }
      }
    }
  }
  std::vector<BlockIndex> sorted(blocks.begin(), blocks.end());
  std::sort(sorted.begin(), sorted.end(), sortedBefore);
  return sorted;
}

std::vector<BlockMesh> meshBlocks(const TsdfMap& map, const std::vector<BlockIndex>& blocks,
                                  const MeshOptions& options) {
  options.validate();
  std::vector<BlockMesh> out(blocks.size());
  // Blocks are independent: chunks on options.num_threads threads, each with its own cache (a +
  // neighbour on a chunk border is meshed twice; the output does not depend on the split).
  parallelForChunks(blocks.size(), resolveThreadCount(options.num_threads),
                            kMeshBlocksPerChunk, [&](std::size_t begin, std::size_t end) {
                              PartCache cache(map, options);
                              for (std::size_t i = begin; i < end; ++i) {
                                out[i] = meshOne(blocks[i], cache);
                              }
                            });
  return out;
}

}  // namespace strata
