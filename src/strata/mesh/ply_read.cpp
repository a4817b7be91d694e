// readPly: loads the file, parses the header, then reads each element through a binary or ascii
// cursor; unknown elements and properties are read and dropped.
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "strata/core/error.h"
#include "strata/mesh/mesh_file_limits.h"
#include "strata/mesh/ply.h"
#include "strata/mesh/internal/ply_format.h"

namespace strata {
namespace {

using detail::PlyElement;
using detail::PlyProperty;

constexpr const char* kVertexRoles[] = {"x", "y", "z", "nx", "ny", "nz", "red", "green", "blue"};
constexpr int kRoleCount = 9;
// Polygons with more corners are surely corruption; the limit also bounds the work per face.
constexpr double kMaxPolygonCorners = 1024;

std::size_t minItemBytes(const PlyElement& element, bool binary) {
  if (!binary) return 2 * element.properties.size();  // one character and a separator per value
  std::size_t bytes = 0;
  for (const PlyProperty& p : element.properties) {
    bytes += detail::plyTypeSize(p.is_list ? p.count_type : p.type);
  }
  return bytes;
}

template <typename Cursor>
std::size_t readListCount(Cursor& cursor, const PlyProperty& property) {
  const double n = cursor.read(property.count_type);
  if (!(n >= 0.0 && n <= kMaxPolygonCorners) || n != std::floor(n)) {
    throw InputError("corrupt list length in property '" + property.name + "'");
  }
  return static_cast<std::size_t>(n);
}

template <typename Cursor>
void skipProperty(Cursor& cursor, const PlyProperty& property) {
  const std::size_t n = property.is_list ? readListCount(cursor, property) : 1;
  for (std::size_t i = 0; i < n; ++i) cursor.read(property.type);
}

/// Positions and colours must be finite floats: a NaN colour would be converted to uchar (undefined
/// behaviour) and a NaN or infinite position poisons every bound computed from the mesh. Normals
/// (roles 3..5) may be NaN, as a degenerate gradient leaves them.
void checkFinite(const std::array<double, kRoleCount>& value, int roles, std::size_t vertex) {
  for (int r = 0; r < roles; ++r) {
    if ((r < 3 || r >= 6) && !(std::abs(value[r]) <= std::numeric_limits<float>::max())) {
      throw InputError("vertex " + std::to_string(vertex) + " has a non-finite " +
                       kVertexRoles[r] + " (" + std::to_string(value[r]) + ")");
    }
  }
}

template <typename Cursor>
void readVertices(Cursor& cursor, const PlyElement& element, Mesh& mesh) {
  std::vector<int> role(element.properties.size(), -1);
  std::array<bool, kRoleCount> present{};
  for (std::size_t p = 0; p < role.size(); ++p) {
    for (int r = 0; r < kRoleCount; ++r) {
      if (!element.properties[p].is_list && element.properties[p].name == kVertexRoles[r]) {
        role[p] = r;
        present[r] = true;
      }
    }
  }
  if (!present[0] || !present[1] || !present[2]) throw InputError("vertex element lacks x, y or z");
  const bool normals = present[3] && present[4] && present[5];
  const bool colors = present[6] && present[7] && present[8];
  for (std::size_t i = 0; i < element.count; ++i) {
    std::array<double, kRoleCount> value{};
    for (std::size_t p = 0; p < role.size(); ++p) {
      if (role[p] < 0) {
        skipProperty(cursor, element.properties[p]);
      } else {
        value[role[p]] = cursor.read(element.properties[p].type);
      }
    }
    checkFinite(value, colors ? kRoleCount : 3, i);
    mesh.vertices.push_back(Eigen::Vector3d(value[0], value[1], value[2]).cast<float>());
    if (normals)
      mesh.normals.push_back(Eigen::Vector3d(value[3], value[4], value[5]).cast<float>());
    if (colors) {
      auto byte = [](double v) { return static_cast<std::uint8_t>(std::clamp(v, 0.0, 255.0)); };
      mesh.colors.push_back({byte(value[6]), byte(value[7]), byte(value[8])});
    }
  }
}

template <typename Cursor>
void readFaces(Cursor& cursor, const PlyElement& element, Mesh& mesh) {
  std::vector<int> corners;
  for (std::size_t i = 0; i < element.count; ++i) {
    for (const PlyProperty& property : element.properties) {
      if (!property.is_list ||
          (property.name != "vertex_indices" && property.name != "vertex_index")) {
        skipProperty(cursor, property);
        continue;
      }
      corners.resize(readListCount(cursor, property));
      if (corners.size() < 3) throw InputError("face " + std::to_string(i) + " has < 3 corners");
      for (int& c : corners) {
        const double index = cursor.read(property.type);
        if (!(index >= 0.0 && index < 2147483647.0) || index != std::floor(index)) {
          throw InputError("face " + std::to_string(i) + " has a corrupt vertex index");
        }
        c = static_cast<int>(index);
      }
      for (std::size_t k = 1; k + 1 < corners.size(); ++k) {  // fan-triangulate polygons
        mesh.triangles.emplace_back(corners[0], corners[k], corners[k + 1]);
      }
      checkMeshCount(mesh.triangles.size(), kMaxMeshTriangles, "kMaxMeshTriangles", "triangle");
    }
  }
}

void checkIndices(const Mesh& mesh) {
  const auto n = static_cast<int>(mesh.vertices.size());
  for (std::size_t i = 0; i < mesh.triangles.size(); ++i) {
    if ((mesh.triangles[i].array() >= n).any()) {
      throw InputError("triangle " + std::to_string(i) + " references a vertex beyond the " +
                       std::to_string(n) + " vertices");
    }
  }
}

/// The header's counts against the mesh limits, before anything is read or allocated. An element
/// without properties takes no bytes, so the file size cannot bound its count: refused, or a
/// corrupt count would loop billions of times over nothing.
void checkDeclaredCounts(const detail::PlyHeader& header) {
  std::size_t vertices = 0;
  std::size_t faces = 0;
  for (const PlyElement& element : header.elements) {
    if (element.properties.empty() && element.count > 0) {
      throw InputError("element '" + element.name + "' declares " +
                       std::to_string(element.count) + " items but no properties");
    }
    // NOTE: each count is checked alone first, so the sums below cannot overflow.
    if (element.name == "vertex") {
      checkMeshCount(element.count, kMaxMeshVertices, "kMaxMeshVertices", "vertex");
      vertices += element.count;
    } else if (element.name == "face") {
      checkMeshCount(element.count, kMaxMeshTriangles, "kMaxMeshTriangles", "face");
      faces += element.count;
    }
  }
  checkMeshCount(vertices, kMaxMeshVertices, "kMaxMeshVertices", "vertex");
  checkMeshCount(faces, kMaxMeshTriangles, "kMaxMeshTriangles", "face");
}

template <typename Cursor>
Mesh readBody(Cursor cursor, const detail::PlyHeader& header) {
  checkDeclaredCounts(header);
  Mesh mesh;
  for (const PlyElement& element : header.elements) {
    if (!cursor.canHold(element.count, minItemBytes(element, header.binary))) {
      throw InputError("truncated: element '" + element.name + "' declares " +
                       std::to_string(element.count) + " items, more than the file holds");
    }
    if (element.name == "vertex") {
      readVertices(cursor, element, mesh);
    } else if (element.name == "face") {
      readFaces(cursor, element, mesh);
    } else {
      for (std::size_t i = 0; i < element.count; ++i) {
        for (const PlyProperty& property : element.properties) skipProperty(cursor, property);
      }
    }
  }
  checkIndices(mesh);
  return mesh;
}

}  // namespace

Mesh readPly(const std::string& path) {
  return parsePly(readTextBounded(path, kMaxMeshFileBytes, "PLY file"), path);
}

Mesh parsePly(const std::string& data, const std::string& path) {
  try {
    const detail::PlyHeader header = detail::parsePlyHeader(data);
    if (header.binary) return readBody(detail::PlyBinaryCursor(data, header.data_offset), header);
    return readBody(detail::PlyAsciiCursor(data, header.data_offset), header);
  } catch (const InputError& e) {
    throw InputError("PLY '" + path + "': " + e.what());
  }
}

}  // namespace strata
