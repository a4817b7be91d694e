// Joining mesh components separated by small gaps (region_growing.h).
#include <algorithm>
#include <cmath>
#include <numeric>
#include <unordered_map>

#include "strata/change/region_growing.h"

namespace strata::change {
namespace {

class UnionFind {
 public:
  explicit UnionFind(std::size_t n) : parent_(n) { std::iota(parent_.begin(), parent_.end(), 0); }
  std::size_t find(std::size_t a) {
    while (parent_[a] != a) a = parent_[a] = parent_[parent_[a]];
    return a;
  }
  void join(std::size_t a, std::size_t b) {
    a = find(a);
    b = find(b);
    // The smaller root wins, so a group is named after its lowest component.
    if (a != b) parent_[std::max(a, b)] = std::min(a, b);
  }

 private:
  std::vector<std::size_t> parent_;
};

std::uint64_t cellKey(const Eigen::Vector3i& c) {
  constexpr std::int64_t kBias = 1 << 20;
  std::uint64_t key = 0;
  for (int k = 0; k < 3; ++k) {
    key |= (static_cast<std::uint64_t>(c[k] + kBias) & 0x1FFFFF) << (21 * k);
  }
  return key;
}

/// (vertex, component) for every vertex of a component's faces.
std::vector<std::pair<int, int>> componentVertices(const Mesh& mesh, const Components& c) {
  std::vector<int> owner(mesh.vertices.size(), -1);
  std::vector<std::pair<int, int>> out;
  for (std::size_t f = 0; f < mesh.triangles.size(); ++f) {
    if (c.component[f] < 0) continue;
    for (int k = 0; k < 3; ++k) {
      const int v = mesh.triangles[f][k];
      if (owner[static_cast<std::size_t>(v)] < 0) {
        owner[static_cast<std::size_t>(v)] = c.component[f];
        out.emplace_back(v, c.component[f]);
      }
    }
  }
  return out;
}

}  // namespace

Components mergeNearbyComponents(const Mesh& mesh, const Components& components, float gap_m) {
  if (!(gap_m > 0.0f) || components.count < 2) return components;
  const std::vector<std::pair<int, int>> vertices = componentVertices(mesh, components);
  // Grid cells of the gap's size: vertices within the gap lie in neighbouring cells.
  std::unordered_map<std::uint64_t, std::vector<std::size_t>> cells;
  const auto cellOf = [&](int v) {
    return Eigen::Vector3i(
        (mesh.vertices[static_cast<std::size_t>(v)] / gap_m).array().floor().cast<int>());
  };
  for (std::size_t i = 0; i < vertices.size(); ++i)
    cells[cellKey(cellOf(vertices[i].first))].push_back(i);
  UnionFind groups(components.count);
  const float gap2 = gap_m * gap_m;
  for (const auto& [v, component] : vertices) {
    const Eigen::Vector3i c = cellOf(v);
    const Eigen::Vector3f& p = mesh.vertices[static_cast<std::size_t>(v)];
    for (int n = 0; n < 27; ++n) {
      const auto it = cells.find(cellKey(c + Eigen::Vector3i(n % 3 - 1, n / 3 % 3 - 1, n / 9 - 1)));
      if (it == cells.end()) continue;
      for (const std::size_t j : it->second) {
        const auto& [w, other] = vertices[j];
        if (other != component &&
            (mesh.vertices[static_cast<std::size_t>(w)] - p).squaredNorm() <= gap2) {
          groups.join(static_cast<std::size_t>(component), static_cast<std::size_t>(other));
        }
      }
    }
  }
  // Renumber: components were numbered by lowest face, and a group takes its lowest member's id.
  Components merged;
  merged.component.assign(components.component.size(), -1);
  std::vector<int> id(components.count, -1);
  for (std::size_t f = 0; f < components.component.size(); ++f) {
    if (components.component[f] < 0) continue;
    const std::size_t root = groups.find(static_cast<std::size_t>(components.component[f]));
    if (id[root] < 0) id[root] = static_cast<int>(merged.count++);
    merged.component[f] = id[root];
  }
  return merged;
}

}  // namespace strata::change
