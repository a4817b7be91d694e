#pragma once
// Mesh checks and comparisons for tests, tools and benchmarks.
#include <cstddef>

#include "strata/mesh/mesh.h"

namespace strata {

struct MeshTopology {
  std::size_t edge_count = 0;            // distinct undirected edges
  std::size_t boundary_edges = 0;        // used by one triangle (a hole's rim)
  std::size_t nonmanifold_edges = 0;     // used by more than two triangles
  std::size_t misoriented_edges = 0;     // two triangles traverse it the same way (winding flips)
  std::size_t degenerate_triangles = 0;  // a vertex index repeated
  long long euler_characteristic = 0;    // V - E + F, V counting vertices used by triangles

  /// Every edge shared by exactly two consistently wound triangles.
  bool isClosedOriented() const {
    return boundary_edges == 0 && nonmanifold_edges == 0 && misoriented_edges == 0 &&
           degenerate_triangles == 0;
  }
};

/// O(F log F). Thread safe.
MeshTopology analyzeTopology(const Mesh& mesh);

/// Symmetric Chamfer distance between vertex sets, metres: the mean, over the vertices of each
/// mesh, of the distance to the nearest vertex of the other, averaged over both directions: (mean_a
/// d(a, B) + mean_b d(b, A)) / 2. Nearest neighbours come from a uniform hash grid with cells about
/// twice the mean edge length. Throws InputError when a mesh has no vertices.
double meshChamferDistance(const Mesh& a, const Mesh& b);

}  // namespace strata
