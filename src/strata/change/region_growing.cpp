#include "strata/change/region_growing.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <deque>
#include <utility>

namespace strata::change {
namespace {

using EdgeFace = std::pair<std::uint64_t, std::uint32_t>;  // (undirected edge key, face)

std::uint64_t edgeKey(int a, int b) {
  const auto lo = static_cast<std::uint64_t>(std::min(a, b));
  const auto hi = static_cast<std::uint64_t>(std::max(a, b));
  return (hi << 32) | lo;
}

std::vector<EdgeFace> sortedEdgeFaces(const Mesh& mesh) {
  std::vector<EdgeFace> edges;
  edges.reserve(mesh.triangles.size() * 3);
  for (std::size_t f = 0; f < mesh.triangles.size(); ++f) {
    const Eigen::Vector3i& t = mesh.triangles[f];
    for (int k = 0; k < 3; ++k) {
      if (t[k] == t[(k + 1) % 3]) continue;  // degenerate edge
      edges.emplace_back(edgeKey(t[k], t[(k + 1) % 3]), static_cast<std::uint32_t>(f));
    }
  }
  std::sort(edges.begin(), edges.end());
  return edges;
}

/// Calls link(a, b) for every pair of faces sharing an edge (once per shared edge).
template <typename Link>
void forEachAdjacentPair(const std::vector<EdgeFace>& edges, Link link) {
  for (std::size_t i = 0; i < edges.size();) {
    std::size_t j = i + 1;
    while (j < edges.size() && edges[j].first == edges[i].first) ++j;
    for (std::size_t a = i; a < j; ++a) {
      for (std::size_t b = a + 1; b < j; ++b) {
        if (edges[a].second != edges[b].second) link(edges[a].second, edges[b].second);
      }
    }
    i = j;
  }
}

/// Area-weighted normals (the cross product, length = 2 * area).
std::vector<Eigen::Vector3f> faceNormals(const Mesh& mesh) {
  std::vector<Eigen::Vector3f> normals(mesh.triangles.size());
  for (std::size_t f = 0; f < mesh.triangles.size(); ++f) {
    const Eigen::Vector3i& t = mesh.triangles[f];
    const Eigen::Vector3f& a = mesh.vertices[static_cast<std::size_t>(t[0])];
    normals[f] = (mesh.vertices[static_cast<std::size_t>(t[1])] - a)
                     .cross(mesh.vertices[static_cast<std::size_t>(t[2])] - a);
  }
  return normals;
}

/// True when the angle between a and b is below the one whose cosine is cos_max; vectors of
/// (near) zero length (degenerate faces, empty means) never block.
bool similar(const Eigen::Vector3f& a, const Eigen::Vector3f& b, float cos_max) {
  const float na = a.norm(), nb = b.norm();
  if (na < 1e-12f || nb < 1e-12f) return true;
  return a.dot(b) >= cos_max * na * nb;
}

float cosDeg(float deg) { return std::cos(deg * 3.14159265358979f / 180.0f); }

constexpr std::uint32_t kUnassigned = ~std::uint32_t{0};

}  // namespace

FaceAdjacency buildFaceAdjacency(const Mesh& mesh) {
  const std::vector<EdgeFace> edges = sortedEdgeFaces(mesh);
  FaceAdjacency adjacency;
  adjacency.offsets.assign(mesh.triangles.size() + 1, 0);
  forEachAdjacentPair(edges, [&](std::uint32_t a, std::uint32_t b) {
    ++adjacency.offsets[a + 1];
    ++adjacency.offsets[b + 1];
  });
  for (std::size_t f = 0; f < mesh.triangles.size(); ++f) {
    adjacency.offsets[f + 1] += adjacency.offsets[f];
  }
  adjacency.neighbours.resize(adjacency.offsets.back());
  std::vector<std::uint32_t> fill(adjacency.offsets.begin(), adjacency.offsets.end() - 1);
  forEachAdjacentPair(edges, [&](std::uint32_t a, std::uint32_t b) {
    adjacency.neighbours[fill[a]++] = b;
    adjacency.neighbours[fill[b]++] = a;
  });
  return adjacency;
}

Regions growSmoothRegions(const Mesh& mesh, const FaceAdjacency& adjacency,
                          float neighbour_angle_deg, float mean_angle_deg) {
  const std::vector<Eigen::Vector3f> normals = faceNormals(mesh);
  const float cos_neighbour = cosDeg(neighbour_angle_deg), cos_mean = cosDeg(mean_angle_deg);
  Regions regions;
  regions.region.assign(mesh.triangles.size(), kUnassigned);
  std::deque<std::uint32_t> queue;
  for (std::uint32_t seed = 0; seed < regions.region.size(); ++seed) {
    if (regions.region[seed] != kUnassigned) continue;
    const auto id = static_cast<std::uint32_t>(regions.count++);
    regions.region[seed] = id;
    Eigen::Vector3f mean = normals[seed];
    queue.push_back(seed);
    while (!queue.empty()) {
      const std::uint32_t f = queue.front();
      queue.pop_front();
      for (std::uint32_t k = adjacency.offsets[f]; k < adjacency.offsets[f + 1]; ++k) {
        const std::uint32_t g = adjacency.neighbours[k];
        if (regions.region[g] != kUnassigned) continue;
        if (!similar(normals[f], normals[g], cos_neighbour)) continue;
        if (!similar(mean, normals[g], cos_mean)) continue;
        regions.region[g] = id;
        mean += normals[g];
        queue.push_back(g);
      }
    }
  }
  return regions;
}

std::vector<bool> labelRegions(const Regions& regions, const std::vector<bool>& face_dynamic,
                               float dynamic_share) {
  std::vector<std::size_t> dynamic(regions.count, 0), total(regions.count, 0);
  for (std::size_t f = 0; f < regions.region.size(); ++f) {
    ++total[regions.region[f]];
    if (face_dynamic[f]) ++dynamic[regions.region[f]];
  }
  std::vector<bool> out(regions.region.size());
  for (std::size_t f = 0; f < out.size(); ++f) {
    const std::uint32_t r = regions.region[f];
    out[f] = static_cast<double>(dynamic[r]) > dynamic_share * static_cast<double>(total[r]);
  }
  return out;
}

Components connectedComponents(const FaceAdjacency& adjacency, const std::vector<bool>& member) {
  Components components;
  components.component.assign(member.size(), -1);
  std::vector<std::uint32_t> stack;
  for (std::uint32_t seed = 0; seed < member.size(); ++seed) {
    if (!member[seed] || components.component[seed] >= 0) continue;
    const int id = static_cast<int>(components.count++);
    components.component[seed] = id;
    stack.push_back(seed);
    while (!stack.empty()) {
      const std::uint32_t f = stack.back();
      stack.pop_back();
      for (std::uint32_t k = adjacency.offsets[f]; k < adjacency.offsets[f + 1]; ++k) {
        const std::uint32_t g = adjacency.neighbours[k];
        if (!member[g] || components.component[g] >= 0) continue;
        components.component[g] = id;
        stack.push_back(g);
      }
    }
  }
  return components;
}

}  // namespace strata::change
