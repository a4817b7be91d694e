#include "strata/lcm/block_mesh_msg.h"

namespace strata::lcm_io {

mesh_block_t toMessage(const BlockMesh& block) {
  mesh_block_t out{};
  for (int a = 0; a < 3; ++a) out.index[a] = block.index[a];
  const Mesh& mesh = block.mesh;
  out.vertices.reserve(mesh.vertices.size());
  for (std::size_t i = 0; i < mesh.vertices.size(); ++i) {
    const Eigen::Vector3f& p = mesh.vertices[i];
    out.vertices.push_back({p.x(), p.y(), p.z()});
    const auto& c = mesh.colors[i];
    out.colors.push_back({c[0], c[1], c[2]});
  }
  for (const Eigen::Vector3i& t : mesh.triangles) out.triangles.push_back({t[0], t[1], t[2]});
  out.num_vertices = static_cast<std::int32_t>(out.vertices.size());
  out.num_triangles = static_cast<std::int32_t>(out.triangles.size());
  return out;
}

std::vector<mesh_block_t> meshBlockMessages(const TsdfMap& map, const std::vector<BlockIndex>& blocks,
                                     const MeshOptions& options) {
  std::vector<mesh_block_t> out;
  out.reserve(blocks.size());
  for (const BlockMesh& block : strata::meshBlocks(map, blocks, options)) {
    out.push_back(toMessage(block));
  }
  return out;
}

Mesh toMesh(const mesh_block_t& block) {
  Mesh mesh;
  for (std::size_t i = 0; i < block.vertices.size(); ++i) {
    const auto& v = block.vertices[i];
    mesh.vertices.emplace_back(v[0], v[1], v[2]);
    const auto& c = block.colors[i];
    mesh.colors.push_back({c[0], c[1], c[2]});
  }
  for (const auto& t : block.triangles) mesh.triangles.emplace_back(t[0], t[1], t[2]);
  return mesh;
}

}  // namespace strata::lcm_io
