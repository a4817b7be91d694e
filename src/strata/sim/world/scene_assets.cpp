#include "strata/sim/world/internal/scene_assets.h"

#include <Eigen/Geometry>
#include <algorithm>

namespace strata::sim {
namespace {

std::vector<Eigen::Vector3f> faceNormals(const Mesh& mesh) {
  std::vector<Eigen::Vector3f> normals;
  normals.reserve(mesh.triangles.size());
  for (const Eigen::Vector3i& t : mesh.triangles) {
    const Eigen::Vector3f& a = mesh.vertices[t[0]];
    const Eigen::Vector3f n = (mesh.vertices[t[1]] - a).cross(mesh.vertices[t[2]] - a);
    const float length = n.norm();
    normals.push_back(length > 0.0f ? Eigen::Vector3f(n / length) : Eigen::Vector3f::UnitZ());
  }
  return normals;
}

/// Copies the mesh into Embree-owned buffers and attaches it to `scene` as geometry `id`.
void attachTriangles(RTCDevice device, RTCScene scene, const Mesh& mesh, unsigned id) {
  RtcGeometryPtr geometry(rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE));
  checkEmbree(device, "rtcNewGeometry(TRIANGLE)");
  auto* vertices = static_cast<float*>(
      rtcSetNewGeometryBuffer(geometry.get(), RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                              3 * sizeof(float), mesh.vertices.size()));
  auto* indices = static_cast<unsigned*>(
      rtcSetNewGeometryBuffer(geometry.get(), RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                              3 * sizeof(unsigned), mesh.triangles.size()));
  checkEmbree(device, "rtcSetNewGeometryBuffer");
  for (std::size_t i = 0; i < mesh.vertices.size(); ++i) {
    std::copy_n(mesh.vertices[i].data(), 3, vertices + 3 * i);
  }
  for (std::size_t i = 0; i < mesh.triangles.size(); ++i) {
    for (int k = 0; k < 3; ++k) indices[3 * i + k] = static_cast<unsigned>(mesh.triangles[i][k]);
  }
  rtcCommitGeometry(geometry.get());
  checkEmbree(device, "rtcCommitGeometry");
  rtcAttachGeometryByID(scene, geometry.get(), id);
  checkEmbree(device, "rtcAttachGeometryByID");
}  // the scene keeps its own reference to the geometry

PartData makePart(const Mesh& mesh, const Material& material) {
  PartData part{mesh, faceNormals(mesh), material};
  part.mesh.colors.clear();
  part.mesh.normals.clear();
  return part;
}

/// Commits a scene made of `parts`, attached as geometries 0, 1, ...
RtcScenePtr buildPartScene(RTCDevice device, const std::vector<PartData>& parts) {
  RtcScenePtr scene = newEmbreeScene(device);
  for (std::size_t i = 0; i < parts.size(); ++i) {
    attachTriangles(device, scene.get(), parts[i].mesh, static_cast<unsigned>(i));
  }
  rtcCommitScene(scene.get());
  checkEmbree(device, "rtcCommitScene");
  return scene;
}

}  // namespace

std::shared_ptr<const SceneAssets> buildSceneAssets(const StaticWorld& static_world,
                                                    const std::vector<ShapeGeometry>& shapes,
                                                    const std::vector<Material>& materials) {
  auto assets = std::make_shared<SceneAssets>();
  assets->device = newEmbreeDevice();
  RTCDevice device = assets->device.get();
  for (const StaticPart& part : static_world.parts) {
    assets->static_parts.push_back(makePart(part.mesh, part.material));
  }
  assets->static_scene = buildPartScene(device, assets->static_parts);
  for (std::size_t i = 0; i < shapes.size(); ++i) {
    std::vector<PartData> parts;
    for (const Mesh& mesh : shapes[i].parts) parts.push_back(makePart(mesh, materials[i]));
    assets->object_scenes.push_back(buildPartScene(device, parts));
    assets->object_parts.push_back(std::move(parts));
  }
  return assets;
}

}  // namespace strata::sim
