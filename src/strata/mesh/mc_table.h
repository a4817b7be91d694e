#pragma once
// Marching-cubes case table, generated from first principles at first use (no pasted table).
//
// Cube conventions: corner c (0..7) sits at offset (c & 1, c >> 1 & 1, c >> 2 & 1). Edge e (0..11)
// runs along axis a = e / 4 from its lower corner to lower | (1 << a); j = e % 4 picks the lower
// corner's bits on the two other axes (a + 1) % 3 (bit 0 of j) and (a + 2) % 3 (bit 1 of j).
// Case bit c is set when corner c is inside (tsdf < 0); tsdf == 0 counts as outside.
#include <array>
#include <cstdint>

namespace strata {

inline constexpr int kCubeEdges = 12;
/// A case with k crossing edges forming l loops has k - 2l triangles; k <= 12 and l >= 1.
inline constexpr int kMaxTrianglesPerCase = 10;

struct CubeEdge {
  int corner0;  // lower corner
  int corner1;  // corner0 + unit step along axis
  int axis;     // 0 = x, 1 = y, 2 = z
};

/// Triangles of one case as triples of cube edges, wound counter-clockwise seen from outside
/// (tsdf > 0), so (v1 - v0) x (v2 - v0) points toward free space.
struct McCase {
  std::uint16_t crossing_edges = 0;  // bit e set when edge e changes sign
  std::uint8_t triangle_count = 0;
  std::array<std::array<std::uint8_t, 3>, kMaxTrianglesPerCase> triangles{};
};

using McTable = std::array<McCase, 256>;

/// The 12 cube edges in the convention above.
const std::array<CubeEdge, kCubeEdges>& cubeEdges();

/// The 256-case table. Thread safe (built once, on first call).
const McTable& marchingCubesTable();

}  // namespace strata
