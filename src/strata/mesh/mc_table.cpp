// Builds the marching-cubes table. For each of the 256 sign configurations:
//  1. On each cube face (corners counter-clockwise seen from outside the cube), every run of
//     consecutive outside corners is cut off by one directed segment, from the edge where the run
//     ends to the edge where it begins, so the outside region lies on the segment's left.
//     NOTE: on an ambiguous face (4 crossings) this separates the two outside corners. The rule
//     looks only at the face's own corners, so both cubes sharing a face cut it alike: watertight.
//  2. Every crossing edge starts exactly one segment and ends exactly one (it borders two faces,
//     which traverse it in opposite directions), so following segments chains them into loops.
//  3. Each loop is triangulated, fan-like where possible. A loop runs counter-clockwise seen from
//     outside (the outside region is on its left on every face), so its triangles face outside.
//     NOTE: no diagonal may join two vertices on one cube face: the cube across that face could
//     use the same vertex pair, and the edge would then be shared by four triangles. Such chords
//     only arise in loops through an ambiguous face; a triangulation avoiding them is searched.
#include "strata/mesh/mc_table.h"

#include <cassert>
#include <stdexcept>
#include <vector>

namespace strata {
namespace {

struct CubeFace {
  std::array<int, 4> corners;  // counter-clockwise seen from outside the cube
  std::array<int, 4> edges;    // edges[k] joins corners[k] and corners[(k + 1) % 4]
};

int edgeIndex(int lower_corner, int axis) {
  const int u = (axis + 1) % 3;
  const int v = (axis + 2) % 3;
  return axis * 4 + ((lower_corner >> u) & 1) + 2 * ((lower_corner >> v) & 1);
}

int edgeBetween(int c0, int c1) {
  const int diff = c0 ^ c1;
  const int axis = diff == 1 ? 0 : (diff == 2 ? 1 : 2);
  return edgeIndex(c0 & c1, axis);
}

std::array<CubeFace, 6> makeFaces() {
  std::array<CubeFace, 6> faces{};
  for (int axis = 0; axis < 3; ++axis) {
    // (axis, u, v) is right-handed, so base, +u, +u+v, +v is counter-clockwise seen from +axis.
    const int u = 1 << ((axis + 1) % 3);
    const int v = 1 << ((axis + 2) % 3);
    for (int side = 0; side < 2; ++side) {
      const int base = side << axis;
      CubeFace& face = faces[axis * 2 + side];
      face.corners = {base, base | u, base | u | v, base | v};
      if (side == 0) face.corners = {base, base | v, base | u | v, base | u};  // seen from -axis
      for (int k = 0; k < 4; ++k) {
        face.edges[k] = edgeBetween(face.corners[k], face.corners[(k + 1) % 4]);
      }
    }
  }
  return faces;
}

/// Step 1: segment_end[e] = end edge of the face segment starting at crossing edge e.
std::array<int, kCubeEdges> faceSegments(int config, const std::array<CubeFace, 6>& faces) {
  std::array<int, kCubeEdges> segment_end;
  segment_end.fill(-1);
  for (const CubeFace& face : faces) {
    std::array<bool, 4> outside{};
    for (int k = 0; k < 4; ++k) outside[k] = ((config >> face.corners[k]) & 1) == 0;
    for (int k = 0; k < 4; ++k) {
      if (!outside[k] || outside[(k + 1) % 4]) continue;  // edge k is not where a run ends
      int first = k;
      while (outside[(first + 3) % 4]) first = (first + 3) % 4;  // walk back to the run's start
      const int start_edge = face.edges[k];
      if (segment_end[start_edge] != -1) throw std::logic_error("mc table: edge starts twice");
      segment_end[start_edge] = face.edges[(first + 3) % 4];
    }
  }
  return segment_end;
}

using Triangle = std::array<std::uint8_t, 3>;

bool onCommonFace(int e0, int e1) {
  const CubeEdge& a = cubeEdges()[e0];
  const CubeEdge& b = cubeEdges()[e1];
  for (int axis = 0; axis < 3; ++axis) {
    const int mask = 1 << axis;
    const int bit = a.corner0 & mask;
    if ((a.corner1 & mask) == bit && (b.corner0 & mask) == bit && (b.corner1 & mask) == bit) {
      return true;
    }
  }
  return false;
}

/// Step 3: triangulates polygon `poly` (loop order) with no face chord as a diagonal. The triangle
/// on side (first, last) takes the latest apex that works, so chord-free loops become plain fans
/// from poly[0]. Exhaustive but tiny: loops have at most 12 corners and run once at startup.
bool triangulate(const std::vector<int>& poly, std::vector<Triangle>& out) {
  const int n = static_cast<int>(poly.size());
  if (n < 3) return true;
  for (int k = n - 2; k >= 1; --k) {
    // Sides of the current polygon are fine; new diagonals must not be face chords.
    if (k > 1 && onCommonFace(poly[0], poly[k])) continue;
    if (k < n - 2 && onCommonFace(poly[k], poly[n - 1])) continue;
    std::vector<Triangle> triangles;
    const std::vector<int> left(poly.begin(), poly.begin() + k + 1);
    const std::vector<int> right(poly.begin() + k, poly.end());
    if (!triangulate(left, triangles) || !triangulate(right, triangles)) continue;
    triangles.push_back({static_cast<std::uint8_t>(poly[0]), static_cast<std::uint8_t>(poly[k]),
                         static_cast<std::uint8_t>(poly[n - 1])});
    out.insert(out.end(), triangles.begin(), triangles.end());
    return true;
  }
  return false;
}

/// Steps 2 and 3 for one configuration.
McCase buildCase(int config, const std::array<CubeFace, 6>& faces) {
  McCase result;
  for (int e = 0; e < kCubeEdges; ++e) {
    const CubeEdge& edge = cubeEdges()[e];
    if (((config >> edge.corner0) & 1) != ((config >> edge.corner1) & 1)) {
      result.crossing_edges |= static_cast<std::uint16_t>(1u << e);
    }
  }
  const std::array<int, kCubeEdges> next = faceSegments(config, faces);
  std::uint16_t visited = 0;
  for (int start = 0; start < kCubeEdges; ++start) {
    if (!((result.crossing_edges >> start) & 1) || ((visited >> start) & 1)) continue;
    std::vector<int> loop;
    for (int e = start; !((visited >> e) & 1); e = next[e]) {
      if (next[e] < 0) throw std::logic_error("mc table: open face segment chain");
      visited |= static_cast<std::uint16_t>(1u << e);
      loop.push_back(e);
    }
    if (next[loop.back()] != start) throw std::logic_error("mc table: loop does not close");
    std::vector<Triangle> triangles;
    if (!triangulate(loop, triangles))
      throw std::logic_error("mc table: no chord-free triangulation");
    if (result.triangle_count + triangles.size() > kMaxTrianglesPerCase) {
      throw std::logic_error("mc table: too many triangles");
    }
    for (const Triangle& tri : triangles) result.triangles[result.triangle_count++] = tri;
  }
  return result;
}

McTable buildTable() {
  const std::array<CubeFace, 6> faces = makeFaces();
  McTable table;
  for (int config = 0; config < 256; ++config) table[config] = buildCase(config, faces);
  return table;
}

}  // namespace

const std::array<CubeEdge, kCubeEdges>& cubeEdges() {
  static const std::array<CubeEdge, kCubeEdges> edges = [] {
    std::array<CubeEdge, kCubeEdges> result{};
    for (int e = 0; e < kCubeEdges; ++e) {
      const int axis = e / 4;
      const int j = e % 4;
      const int lower = ((j & 1) << ((axis + 1) % 3)) | (((j >> 1) & 1) << ((axis + 2) % 3));
      result[e] = {lower, lower | (1 << axis), axis};
      assert(edgeIndex(lower, axis) == e);
    }
    return result;
  }();
  return edges;
}

const McTable& marchingCubesTable() {
  static const McTable table = buildTable();
  return table;
}

}  // namespace strata
