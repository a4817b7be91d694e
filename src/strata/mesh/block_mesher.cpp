#include "strata/mesh/internal/block_mesher.h"

#include <cmath>
#include <stdexcept>

#include "strata/mesh/mc_table.h"

namespace strata::detail {
namespace {

Eigen::Vector3i cornerOffset(int corner) {
  return Eigen::Vector3i(corner & 1, (corner >> 1) & 1, (corner >> 2) & 1);
}

std::array<std::uint8_t, 3> lerpColor(std::uint32_t c0, std::uint32_t c1, float t) {
  std::array<std::uint8_t, 3> rgb{};
  for (int i = 0; i < 3; ++i) {
    const float a = static_cast<float>((c0 >> (8 * i)) & 0xFF);
    const float b = static_cast<float>((c1 >> (8 * i)) & 0xFF);
    rgb[i] = static_cast<std::uint8_t>(std::lround(a + t * (b - a)));
  }
  return rgb;
}

}  // namespace

BlockMesher::BlockMesher(const TsdfMap& map, const MeshOptions& options)
    : map_(map),
      options_(options),
      voxel_size_m_(map.config().voxel_size_m),
      max_jump_m_(options.max_crossing_jump_truncations * map.config().truncationDistance()) {}

BlockMeshPart BlockMesher::mesh(const BlockIndex& block) {
  loadHalo(block);
  classifyCubes();
  BlockMeshPart part;
  createVertices(block, part);
  emitTriangles(part);
  return part;
}

void BlockMesher::loadHalo(const BlockIndex& block) {
  // The 27 blocks around (and including) this one; the halo reaches into those on every side.
  std::array<const TsdfBlock*, 27> neighbours{};
  for (int i = 0; i < 27; ++i) {
    neighbours[i] = map_.findBlock(block + Eigen::Vector3i(i % 3 - 1, i / 3 % 3 - 1, i / 9 - 1));
  }
  auto split = [](int c, int& local) {  // block offset (0..2) of local coordinate c
    const int offset = c < 0 ? 0 : (c >= kBlockEdge ? 2 : 1);
    local = c - (offset - 1) * kBlockEdge;
    return offset;
  };
  for (int z = -1; z <= kBlockEdge + 1; ++z) {
    for (int y = -1; y <= kBlockEdge + 1; ++y) {
      for (int x = -1; x <= kBlockEdge + 1; ++x) {
        int lx = 0, ly = 0, lz = 0;
        const int n = split(x, lx) + 3 * split(y, ly) + 9 * split(z, lz);
        const int h = haloIndex(x, y, z);
        const TsdfVoxel* voxel =
            neighbours[n] == nullptr ? nullptr : &(*neighbours[n])[linearVoxelIndex(lx, ly, lz)];
        // NOTE: a non-finite tsdf counts as unobserved so it cannot poison vertex positions.
        observed_[h] = voxel != nullptr && voxel->weight >= options_.min_weight &&
                       std::isfinite(voxel->tsdf_m);
        tsdf_[h] = observed_[h] ? voxel->tsdf_m : 0.0f;
        color_[h] = observed_[h] ? voxel->color_rgba : 0u;
      }
    }
  }
}

std::uint8_t BlockMesher::classifyCube(int x, int y, int z) const {
  std::array<int, 8> h{};
  int config = 0;
  for (int c = 0; c < 8; ++c) {
    h[c] = haloIndex(x + (c & 1), y + ((c >> 1) & 1), z + ((c >> 2) & 1));
    if (!observed_[h[c]]) return 0;
    if (tsdf_[h[c]] < 0.0f) config |= 1 << c;
  }
  if (config == 0 || config == 255) return 0;
  // Truncation seam: a sign change that jumps too far is not a surface (see MeshOptions).
  const McCase& mc = marchingCubesTable()[config];
  for (int e = 0; e < kCubeEdges; ++e) {
    if (!((mc.crossing_edges >> e) & 1)) continue;
    const CubeEdge& edge = cubeEdges()[e];
    if (std::abs(tsdf_[h[edge.corner0]] - tsdf_[h[edge.corner1]]) > max_jump_m_) return 0;
  }
  return static_cast<std::uint8_t>(config);
}

void BlockMesher::classifyCubes() {
  for (int z = -1; z < kBlockEdge; ++z) {
    for (int y = -1; y < kBlockEdge; ++y) {
      for (int x = -1; x < kBlockEdge; ++x) cube_case_[cubeIndex(x, y, z)] = classifyCube(x, y, z);
    }
  }
}

bool BlockMesher::edgeHasVertex(const Eigen::Vector3i& v, int axis) const {
  const int h0 = haloIndex(v.x(), v.y(), v.z());
  const int h1 = haloIndex(v.x() + (axis == 0), v.y() + (axis == 1), v.z() + (axis == 2));
  if ((tsdf_[h0] < 0.0f) == (tsdf_[h1] < 0.0f)) return false;
  // The four cubes around the edge have lower corners v - s * e_u - t * e_w.
  const int u = (axis + 1) % 3;
  const int w = (axis + 2) % 3;
  for (int s = 0; s < 2; ++s) {
    for (int t = 0; t < 2; ++t) {
      Eigen::Vector3i lower = v;
      lower[u] -= s;
      lower[w] -= t;
      if (cube_case_[cubeIndex(lower.x(), lower.y(), lower.z())] != 0) return true;
    }
  }
  return false;
}

Eigen::Vector3f BlockMesher::gradient(int h) const {
  // Central differences; one-sided where a neighbour is unobserved, 0 where both are.
  static constexpr std::array<int, 3> kStride = {1, kHaloEdge, kHaloEdge * kHaloEdge};
  Eigen::Vector3f g = Eigen::Vector3f::Zero();
  for (int a = 0; a < 3; ++a) {
    const int lo = h - kStride[a];
    const int hi = h + kStride[a];
    if (observed_[lo] && observed_[hi]) {
      g[a] = (tsdf_[hi] - tsdf_[lo]) / (2.0f * voxel_size_m_);
    } else if (observed_[hi]) {
      g[a] = (tsdf_[hi] - tsdf_[h]) / voxel_size_m_;
    } else if (observed_[lo]) {
      g[a] = (tsdf_[h] - tsdf_[lo]) / voxel_size_m_;
    }
  }
  return g;
}

void BlockMesher::addVertex(const BlockIndex& block, const Eigen::Vector3i& v, int axis,
                            BlockMeshPart& part) const {
  const int h0 = haloIndex(v.x(), v.y(), v.z());
  const int h1 = haloIndex(v.x() + (axis == 0), v.y() + (axis == 1), v.z() + (axis == 2));
  const float d0 = tsdf_[h0];
  const float d1 = tsdf_[h1];
  const float t = std::min(1.0f, std::max(0.0f, d0 / (d0 - d1)));  // signs differ: d0 != d1
  Eigen::Vector3f position = voxelCenter(block * kBlockEdge + v, voxel_size_m_);
  position[axis] += t * voxel_size_m_;
  part.vertices.push_back(position);
  part.colors.push_back(lerpColor(color_[h0], color_[h1], t));
  if (!options_.compute_normals) return;
  Eigen::Vector3f normal = (1.0f - t) * gradient(h0) + t * gradient(h1);
  const float norm = normal.norm();
  if (norm > 1e-6f) {
    normal /= norm;
  } else {  // flat gradient (clamped band): the edge direction toward positive tsdf
    normal = Eigen::Vector3f::Zero();
    normal[axis] = d1 > d0 ? 1.0f : -1.0f;
  }
  part.normals.push_back(normal);
}

void BlockMesher::createVertices(const BlockIndex& block, BlockMeshPart& part) {
  slot_vertex_.fill(-1);
  for (int z = 0; z < kBlockEdge; ++z) {
    for (int y = 0; y < kBlockEdge; ++y) {
      for (int x = 0; x < kBlockEdge; ++x) {
        for (int axis = 0; axis < 3; ++axis) {
          const Eigen::Vector3i v(x, y, z);
          if (!edgeHasVertex(v, axis)) continue;
          const int slot = linearVoxelIndex(x, y, z) * 3 + axis;
          slot_vertex_[slot] = static_cast<std::int32_t>(part.vertices.size());
          part.vertex_slots.push_back(static_cast<std::uint16_t>(slot));
          addVertex(block, v, axis, part);
        }
      }
    }
  }
}

void BlockMesher::emitTriangles(BlockMeshPart& part) const {
  const McTable& table = marchingCubesTable();
  for (int z = 0; z < kBlockEdge; ++z) {
    for (int y = 0; y < kBlockEdge; ++y) {
      for (int x = 0; x < kBlockEdge; ++x) {
        const McCase& mc = table[cube_case_[cubeIndex(x, y, z)]];
        for (int i = 0; i < mc.triangle_count; ++i) {
          std::array<std::uint32_t, 3> refs{};
          for (int k = 0; k < 3; ++k) {
            const CubeEdge& edge = cubeEdges()[mc.triangles[i][k]];
            const Eigen::Vector3i lower = Eigen::Vector3i(x, y, z) + cornerOffset(edge.corner0);
            const Eigen::Vector3i owner = (lower.array() >= kBlockEdge).cast<int>();
            const Eigen::Vector3i local = lower - owner * kBlockEdge;
            const int slot = linearVoxelIndex(local.x(), local.y(), local.z()) * 3 + edge.axis;
            const std::uint32_t code = owner.x() | owner.y() << 1 | owner.z() << 2;
            if (code == 0 && slot_vertex_[slot] < 0)
              throw std::logic_error("mesher: missing vertex");
            refs[k] = code == 0 ? static_cast<std::uint32_t>(slot_vertex_[slot])
                                : kExternalVertex | code << 11 | static_cast<std::uint32_t>(slot);
          }
          part.triangles.push_back(refs);
        }
      }
    }
  }
}

}  // namespace strata::detail
