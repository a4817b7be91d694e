// writePly: the whole file is serialised in memory, then written atomically (core/atomic_file.h:
// a temporary in the target folder renamed over the target; the old file kept on any failure).
#include <sstream>
#include <string>
#include <vector>

#include "strata/core/atomic_file.h"
#include "strata/core/error.h"
#include "strata/mesh/ply.h"

// NOTE: the body is copied from memory as is; PLY here is little-endian.
static_assert(__BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__, "writePly assumes a little-endian host");

namespace strata {
namespace {

template <typename T>
void append(std::string& out, const T& value) {
  out.append(reinterpret_cast<const char*>(&value), sizeof(T));
}

void checkConsistent(const std::string& path, const Mesh& mesh) {
  const std::size_t n = mesh.vertices.size();
  if ((mesh.hasNormals() && mesh.normals.size() != n) ||
      (mesh.hasColors() && mesh.colors.size() != n)) {
    throw Error("cannot write PLY '" + path + "': normals/colours do not match the vertex count");
  }
  for (const Eigen::Vector3i& tri : mesh.triangles) {
    if ((tri.array() < 0).any() || (tri.array() >= static_cast<int>(n)).any()) {
      throw Error("cannot write PLY '" + path + "': a triangle references a missing vertex");
    }
  }
}

std::string serialise(const Mesh& mesh) {
  std::ostringstream header;
  header << "ply\nformat binary_little_endian 1.0\ncomment written by strata\n"
         << "element vertex " << mesh.vertices.size() << "\n"
         << "property float x\nproperty float y\nproperty float z\n";
  if (mesh.hasNormals()) header << "property float nx\nproperty float ny\nproperty float nz\n";
  if (mesh.hasColors()) header << "property uchar red\nproperty uchar green\nproperty uchar blue\n";
  header << "element face " << mesh.triangles.size() << "\n"
         << "property list uchar int vertex_indices\nend_header\n";
  std::string out = header.str();
  const std::size_t vertex_bytes = 12 + (mesh.hasNormals() ? 12 : 0) + (mesh.hasColors() ? 3 : 0);
  out.reserve(out.size() + mesh.vertices.size() * vertex_bytes + mesh.triangles.size() * 13);
  for (std::size_t i = 0; i < mesh.vertices.size(); ++i) {
    for (int k = 0; k < 3; ++k) append(out, mesh.vertices[i][k]);
    if (mesh.hasNormals()) {
      for (int k = 0; k < 3; ++k) append(out, mesh.normals[i][k]);
    }
    if (mesh.hasColors()) out.append(reinterpret_cast<const char*>(mesh.colors[i].data()), 3);
  }
  for (const Eigen::Vector3i& tri : mesh.triangles) {
    append(out, std::uint8_t{3});
    for (int k = 0; k < 3; ++k) append(out, static_cast<std::int32_t>(tri[k]));
  }
  return out;
}

}  // namespace

void writePly(const std::string& path, const Mesh& mesh) {
  checkConsistent(path, mesh);
  const std::string data = serialise(mesh);
  writeFileAtomically(path, std::vector<std::uint8_t>(data.begin(), data.end()));
}

}  // namespace strata
