#pragma once
// A triangle mesh as produced by marching cubes and read/written as PLY.
#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <vector>

namespace strata {

/// Indexed triangle mesh. `normals` and `colors` are either empty or one per vertex. Triangles wind
/// counter-clockwise seen from the side their normal points to (for TSDF meshes: free space).
struct Mesh {
  std::vector<Eigen::Vector3f> vertices;
  std::vector<Eigen::Vector3f> normals;
  std::vector<std::array<std::uint8_t, 3>> colors;
  std::vector<Eigen::Vector3i> triangles;

  bool empty() const { return triangles.empty(); }
  bool hasNormals() const { return !normals.empty(); }
  bool hasColors() const { return !colors.empty(); }
};

}  // namespace strata
