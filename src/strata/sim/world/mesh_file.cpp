#include "strata/sim/world/mesh_file.h"

#include <Eigen/Geometry>
#include <fstream>
#include <sstream>

#include "strata/core/error.h"
#include "strata/mesh/mesh_file_limits.h"
#include "strata/mesh/ply.h"

namespace strata::sim {
namespace {

bool endsWith(const std::string& text, const std::string& suffix) {
  if (text.size() < suffix.size()) return false;
  for (std::size_t i = 0; i < suffix.size(); ++i) {
    if (std::tolower(static_cast<unsigned char>(text[text.size() - suffix.size() + i])) !=
        suffix[i]) {
      return false;
    }
  }
  return true;
}

/// Index of an OBJ face corner ("7", "7/2", "7/2/5", "7//5", "-1") as 0-based, or -1 when bad.
long objIndex(const std::string& token, std::size_t vertex_count) {
  long index = 0;
  try {
    index = std::stol(token.substr(0, token.find('/')));
  } catch (const std::exception&) {
    return -1;
  }
  if (index < 0)
    index += static_cast<long>(vertex_count);  // relative: -1 is the last vertex
  else
    index -= 1;
  return (index >= 0 && index < static_cast<long>(vertex_count)) ? index : -1;
}

void parseFace(std::istringstream& in, Mesh& mesh, const std::string& where) {
  std::vector<int> corners;
  std::string token;
  while (in >> token) {
    const long index = objIndex(token, mesh.vertices.size());
    if (index < 0) throw InputError(where + ": bad or out-of-range vertex index '" + token + "'");
    corners.push_back(static_cast<int>(index));
  }
  if (corners.size() < 3) throw InputError(where + ": a face needs at least 3 vertices");
  checkMeshCount(mesh.triangles.size() + corners.size() - 2, kMaxMeshTriangles,
                 "kMaxMeshTriangles", "triangle");
  for (std::size_t i = 1; i + 1 < corners.size(); ++i) {
    mesh.triangles.emplace_back(corners[0], corners[i], corners[i + 1]);
  }
}

}  // namespace

Mesh readObj(const std::string& path) {
  checkFileSize(path, kMaxMeshFileBytes, "OBJ file");
  std::ifstream file(path);
  if (!file) throw InputError("cannot open mesh file '" + path + "'");
  return readObj(file, path);
}

Mesh readObj(std::istream& file, const std::string& path) {
  Mesh mesh;
  std::string line;
  for (int number = 1; std::getline(file, line); ++number) {
    std::istringstream in(line);
    std::string tag;
    in >> tag;
    const std::string where = path + ":" + std::to_string(number);
    if (tag == "v") {
      Eigen::Vector3f v;
      if (!(in >> v.x() >> v.y() >> v.z()) || !v.allFinite()) {
        throw InputError(where + ": expected 'v x y z' with 3 numbers");
      }
      checkMeshCount(mesh.vertices.size() + 1, kMaxMeshVertices, "kMaxMeshVertices", "vertex");
      mesh.vertices.push_back(v);
    } else if (tag == "f") {
      parseFace(in, mesh, where);
    }
  }
  if (mesh.triangles.empty()) throw InputError(path + ": no faces (f lines) in the OBJ file");
  return mesh;
}

Mesh readMeshFile(const std::string& path) {
  Mesh mesh = endsWith(path, ".obj") ? readObj(path) : readPly(path);
  if (mesh.triangles.empty()) throw InputError(path + ": the mesh has no triangles");
  mesh.normals.clear();  // the world recomputes nothing from them; keep parts uniform
  mesh.colors.clear();
  return mesh;
}

Mesh loadShapeMesh(ShapeSpec& shape) {
  Mesh mesh = readMeshFile(shape.mesh_path);
  Eigen::Matrix3f R = Eigen::Matrix3f::Identity();
  if (shape.y_up) {  // (x, y, z) -> (x, -z, y): +y becomes +z, right-handed
    R << 1, 0, 0, 0, 0, -1, 0, 1, 0;
  }
  Eigen::AlignedBox3f box;
  for (Eigen::Vector3f& v : mesh.vertices) {
    v = static_cast<float>(shape.scale) * (R * v);
    box.extend(v);
  }
  const Eigen::Vector3f centre = box.center();
  const Eigen::Vector3f offset(centre.x(), centre.y(), box.min().z());
  for (Eigen::Vector3f& v : mesh.vertices) v -= offset;
  shape.size_m = box.sizes().cast<double>();
  return mesh;
}

}  // namespace strata::sim
