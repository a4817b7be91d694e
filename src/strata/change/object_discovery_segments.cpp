// Turning a set of faces into a discovered object: its own mesh, its shape, its bounds.
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>

#include "strata/change/internal/objects_steps.h"

namespace strata::change::detail {

Mesh subMesh(const Mesh& mesh, const std::vector<std::uint32_t>& faces) {
  Mesh out;
  std::vector<int> remap(mesh.vertices.size(), -1);
  out.triangles.reserve(faces.size());
  for (const std::uint32_t f : faces) {
    Eigen::Vector3i tri;
    for (int k = 0; k < 3; ++k) {
      const auto v = static_cast<std::size_t>(mesh.triangles[f][k]);
      if (remap[v] < 0) {
        remap[v] = static_cast<int>(out.vertices.size());
        out.vertices.push_back(mesh.vertices[v]);
        if (mesh.hasNormals()) out.normals.push_back(mesh.normals[v]);
        if (mesh.hasColors()) out.colors.push_back(mesh.colors[v]);
      }
      tri[k] = remap[v];
    }
    out.triangles.push_back(tri);
  }
  return out;
}

float singularValueRatio(const Mesh& mesh) {
  const std::size_t n = mesh.vertices.size();
  if (n < 3) return 0.0f;
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (const Eigen::Vector3f& v : mesh.vertices) mean += v.cast<double>();
  mean /= static_cast<double>(n);
  Eigen::Matrix3d scatter = Eigen::Matrix3d::Zero();
  for (const Eigen::Vector3f& v : mesh.vertices) {
    const Eigen::Vector3d d = v.cast<double>() - mean;
    scatter += d * d.transpose();
  }
  // The singular values of the centred n x 3 vertex matrix are the square roots of the
  // eigenvalues of its scatter matrix (ascending from Eigen's self-adjoint solver).
  const Eigen::Vector3d eig =
      Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(scatter).eigenvalues().cwiseMax(0.0);
  if (eig[2] <= 0.0) return 0.0f;
  return static_cast<float>(std::sqrt(eig[0] / eig[2]));
}

DiscoveredObject makeObject(Mesh mesh, int session) {
  DiscoveredObject object;
  object.session = session;
  object.vertex_count = mesh.vertices.size();
  for (const Eigen::Vector3f& v : mesh.vertices) {
    object.bbox.extend(v);
    object.centroid += v;
  }
  if (!mesh.vertices.empty()) object.centroid /= static_cast<float>(mesh.vertices.size());
  object.mesh = std::move(mesh);
  return object;
}

}  // namespace strata::change::detail
