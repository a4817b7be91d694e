#include <algorithm>
#include <cstdint>
#include <vector>

#include "strata/mesh/mesh_metrics.h"

namespace strata {
namespace {

struct DirectedEdge {
  std::uint64_t key;  // min index << 32 | max index
  bool forward;       // traversed from min to max
  bool operator<(const DirectedEdge& o) const { return key < o.key; }
};

std::vector<DirectedEdge> collectEdges(const Mesh& mesh, std::size_t& degenerate) {
  std::vector<DirectedEdge> edges;
  edges.reserve(mesh.triangles.size() * 3);
  for (const Eigen::Vector3i& tri : mesh.triangles) {
    if (tri[0] == tri[1] || tri[1] == tri[2] || tri[2] == tri[0]) {
      ++degenerate;
      continue;
    }
    for (int k = 0; k < 3; ++k) {
      const auto from = static_cast<std::uint32_t>(tri[k]);
      const auto to = static_cast<std::uint32_t>(tri[(k + 1) % 3]);
      const std::uint64_t lo = std::min(from, to);
      const std::uint64_t hi = std::max(from, to);
      edges.push_back({lo << 32 | hi, from < to});
    }
  }
  std::sort(edges.begin(), edges.end());
  return edges;
}

std::size_t countUsedVertices(const Mesh& mesh) {
  std::vector<bool> used(mesh.vertices.size(), false);
  for (const Eigen::Vector3i& tri : mesh.triangles) {
    for (int k = 0; k < 3; ++k) {
      const auto v = static_cast<std::size_t>(tri[k]);
      if (tri[k] >= 0 && v < used.size()) used[v] = true;
    }
  }
  return static_cast<std::size_t>(std::count(used.begin(), used.end(), true));
}

}  // namespace

MeshTopology analyzeTopology(const Mesh& mesh) {
  MeshTopology topology;
  const std::vector<DirectedEdge> edges = collectEdges(mesh, topology.degenerate_triangles);
  for (std::size_t begin = 0; begin < edges.size();) {
    std::size_t end = begin;
    std::size_t forward = 0;
    for (; end < edges.size() && edges[end].key == edges[begin].key; ++end) {
      forward += edges[end].forward;
    }
    const std::size_t uses = end - begin;
    ++topology.edge_count;
    if (uses == 1) ++topology.boundary_edges;
    if (uses > 2) ++topology.nonmanifold_edges;
    if (uses == 2 && forward != 1) ++topology.misoriented_edges;
    begin = end;
  }
  topology.euler_characteristic = static_cast<long long>(countUsedVertices(mesh)) -
                                  static_cast<long long>(topology.edge_count) +
                                  static_cast<long long>(mesh.triangles.size());
  return topology;
}

}  // namespace strata
