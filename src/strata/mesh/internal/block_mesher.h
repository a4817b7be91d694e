#pragma once
// Marching cubes for one block (internal to extractMesh).
//
// Vertex ownership: the vertex on the edge from global voxel v along axis a belongs to the block
// holding v, which computes it once. It exists when the edge changes sign and one of the four cubes
// around the edge is active, a test the owner can make because it loads a one-voxel halo around its
// block (two on the + side: cubes reach one voxel further, central differences one more).
// A block's triangles cover the cubes whose lower corner lies in the block; corners that belong to
// a + neighbour's edges are referenced by (neighbour, edge slot) and resolved after all blocks.
#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <vector>

#include "strata/map/tsdf_map.h"
#include "strata/mesh/extract_mesh.h"

namespace strata::detail {

/// Vertex reference with this bit set: (neighbour offset bits x | y << 1 | z << 2) << 11 | slot.
inline constexpr std::uint32_t kExternalVertex = 1u << 31;
/// Edge slot of local voxel (x, y, z) along axis a: linearVoxelIndex(x, y, z) * 3 + a (< 2^11).
inline constexpr int kEdgeSlotsPerBlock = kVoxelsPerBlock * 3;

struct BlockMeshPart {
  std::vector<Eigen::Vector3f> vertices;
  std::vector<Eigen::Vector3f> normals;
  std::vector<std::array<std::uint8_t, 3>> colors;
  std::vector<std::uint16_t> vertex_slots;              // edge slot of each vertex, ascending
  std::vector<std::array<std::uint32_t, 3>> triangles;  // local vertex index or kExternalVertex ref
};

/// Holds per-thread scratch; not thread safe, use one per thread.
class BlockMesher {
 public:
  BlockMesher(const TsdfMap& map, const MeshOptions& options);
  BlockMeshPart mesh(const BlockIndex& block);

 private:
  // Halo covers local voxel coordinates -1..9 on each axis.
  static constexpr int kHaloEdge = kBlockEdge + 3;
  static constexpr int kHaloSize = kHaloEdge * kHaloEdge * kHaloEdge;
  // Cubes by lower corner, local -1..7 on each axis.
  static constexpr int kCubeGridEdge = kBlockEdge + 1;
  static constexpr int kCubeGridSize = kCubeGridEdge * kCubeGridEdge * kCubeGridEdge;

  static int haloIndex(int x, int y, int z) {
    return (x + 1) + kHaloEdge * ((y + 1) + kHaloEdge * (z + 1));
  }
  static int cubeIndex(int x, int y, int z) {
    return (x + 1) + kCubeGridEdge * ((y + 1) + kCubeGridEdge * (z + 1));
  }

  void loadHalo(const BlockIndex& block);
  void classifyCubes();
  std::uint8_t classifyCube(int x, int y, int z) const;
  bool edgeHasVertex(const Eigen::Vector3i& v, int axis) const;
  void addVertex(const BlockIndex& block, const Eigen::Vector3i& v, int axis,
                 BlockMeshPart& part) const;
  Eigen::Vector3f gradient(int h) const;
  void createVertices(const BlockIndex& block, BlockMeshPart& part);
  void emitTriangles(BlockMeshPart& part) const;

  const TsdfMap& map_;
  MeshOptions options_;
  float voxel_size_m_;
  float max_jump_m_;
  std::array<float, kHaloSize> tsdf_{};
  std::array<std::uint32_t, kHaloSize> color_{};
  std::array<bool, kHaloSize> observed_{};
  std::array<std::uint8_t, kCubeGridSize> cube_case_{};         // 0 = cube emits nothing
  std::array<std::int32_t, kEdgeSlotsPerBlock> slot_vertex_{};  // -1 = no vertex
};

}  // namespace strata::detail
