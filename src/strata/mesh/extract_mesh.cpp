// extractMesh: phase 1 meshes every block independently (parallel), phase 2 concatenates the parts
// in sorted block order and resolves vertex references into + neighbours (parallel).
#include "strata/mesh/extract_mesh.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <stdexcept>
#include <string>
#include <unordered_map>

#include "strata/core/error.h"
#include "strata/mesh/internal/block_mesher.h"
#include "strata/core/parallel_for.h"

namespace strata {
namespace {

using detail::BlockMeshPart;

// Blocks per claimed chunk: large enough to amortise the atomic, small enough to balance.
constexpr std::size_t kPartsPerChunk = 32;

struct PartLayout {
  std::vector<BlockIndex> blocks;  // sorted
  std::unordered_map<BlockIndex, std::size_t, BlockIndexHash> position;
  std::vector<BlockMeshPart> parts;
  std::vector<std::size_t> vertex_offset;  // prefix sums, one extra at the end
  std::vector<std::size_t> triangle_offset;
};

std::uint32_t resolveExternal(const PartLayout& layout, std::size_t part, std::uint32_t ref) {
  const std::uint32_t code = (ref >> 11) & 7u;
  const auto slot = static_cast<std::uint16_t>(ref & 0x7FFu);
  const BlockIndex neighbour =
      layout.blocks[part] + Eigen::Vector3i(code & 1u, (code >> 1) & 1u, (code >> 2) & 1u);
  const auto it = layout.position.find(neighbour);
  if (it == layout.position.end()) throw std::logic_error("mesher: vertex in a missing block");
  const std::vector<std::uint16_t>& slots = layout.parts[it->second].vertex_slots;
  const auto found = std::lower_bound(slots.begin(), slots.end(), slot);
  if (found == slots.end() || *found != slot) throw std::logic_error("mesher: missing + vertex");
  return static_cast<std::uint32_t>(layout.vertex_offset[it->second] + (found - slots.begin()));
}

void copyPart(const PartLayout& layout, std::size_t i, Mesh& mesh) {
  const BlockMeshPart& part = layout.parts[i];
  const std::size_t v0 = layout.vertex_offset[i];
  // NOTE: only attributes the mesh has: begin() + v0 of an empty vector (no normals asked for, no
  // colour) is pointer arithmetic on null, undefined even when nothing is copied
  // (UndefinedBehaviorSanitizer found it).
  const auto copy_into = [v0](const auto& from, auto& to) {
    if (from.empty()) return;
    std::copy(from.begin(), from.end(), to.begin() + static_cast<std::ptrdiff_t>(v0));
  };
  copy_into(part.vertices, mesh.vertices);
  copy_into(part.normals, mesh.normals);
  copy_into(part.colors, mesh.colors);
  std::size_t out = layout.triangle_offset[i];
  for (const auto& refs : part.triangles) {
    Eigen::Vector3i& tri = mesh.triangles[out++];
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t ref = refs[k];
      const std::size_t index =
          (ref & detail::kExternalVertex) ? resolveExternal(layout, i, ref) : v0 + ref;
      tri[k] = static_cast<int>(index);
    }
  }
}

Mesh assemble(const PartLayout& layout, bool with_normals, int threads) {
  const std::size_t vertex_count = layout.vertex_offset.back();
  if (vertex_count > static_cast<std::size_t>(std::numeric_limits<int>::max())) {
    throw Error("extractMesh: " + std::to_string(vertex_count) + " vertices exceed int indices");
  }
  Mesh mesh;
  mesh.vertices.resize(vertex_count);
  mesh.colors.resize(vertex_count);
  if (with_normals) mesh.normals.resize(vertex_count);
  mesh.triangles.resize(layout.triangle_offset.back());
  parallelForChunks(layout.parts.size(), threads, kPartsPerChunk,
                            [&](std::size_t begin, std::size_t end) {
                              for (std::size_t i = begin; i < end; ++i) copyPart(layout, i, mesh);
                            });
  return mesh;
}

}  // namespace

void MeshOptions::validate() const {
  if (!std::isfinite(min_weight) || min_weight <= 0.0f) {
    throw InputError(
        "invalid mesh options: min_weight must be finite and positive (0 would mesh "
        "unobserved voxels)");
  }
  if (!std::isfinite(max_crossing_jump_truncations) || max_crossing_jump_truncations <= 0.0f) {
    throw InputError("invalid mesh options: max_crossing_jump_truncations must be positive");
  }
  if (num_threads < 0) throw InputError("invalid mesh options: num_threads must be >= 0");
}

Mesh extractMesh(const TsdfMap& map, const MeshOptions& options) {
  options.validate();
  const int threads = resolveThreadCount(options.num_threads);
  PartLayout layout;
  layout.blocks = map.sortedBlockIndices();
  layout.position.reserve(layout.blocks.size());
  for (std::size_t i = 0; i < layout.blocks.size(); ++i) layout.position[layout.blocks[i]] = i;

  layout.parts.resize(layout.blocks.size());
  parallelForChunks(layout.blocks.size(), threads, kPartsPerChunk,
                            [&](std::size_t begin, std::size_t end) {
                              detail::BlockMesher mesher(map, options);
                              for (std::size_t i = begin; i < end; ++i) {
                                layout.parts[i] = mesher.mesh(layout.blocks[i]);
                              }
                            });

  layout.vertex_offset.assign(1, 0);
  layout.triangle_offset.assign(1, 0);
  for (const BlockMeshPart& part : layout.parts) {
    layout.vertex_offset.push_back(layout.vertex_offset.back() + part.vertices.size());
    layout.triangle_offset.push_back(layout.triangle_offset.back() + part.triangles.size());
  }
  return assemble(layout, options.compute_normals, threads);
}

}  // namespace strata
