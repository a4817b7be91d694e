#pragma once
// The Embree scenes a world's sessions share (internal): one scene of all static parts and one
// scene per object shape, each part its own geometry (so ray crossings can be counted per closed
// part). A session's WorldScene only adds a small top-level scene of instances on top.
// Immutable after buildSceneAssets(); Embree reads it from any thread.
#include <memory>
#include <vector>

#include "strata/mesh/mesh.h"
#include "strata/sim/ray_scene.h"
#include "strata/sim/world/internal/embree_handles.h"
#include "strata/sim/world/internal/static_geometry.h"

namespace strata::sim {

/// One closed part as Embree sees it, with what hits and distance queries need to look up.
struct PartData {
  Mesh mesh;  // in its scene's frame (world for static parts, object frame for objects)
  std::vector<Eigen::Vector3f> face_normals;  // unit, outward, per triangle
  Material material;
};

struct SceneAssets {
  RtcDevicePtr device;
  RtcScenePtr static_scene;
  std::vector<PartData> static_parts;               // by Embree geometry id in static_scene
  std::vector<RtcScenePtr> object_scenes;           // by object index (id - 1)
  std::vector<std::vector<PartData>> object_parts;  // [object index][geometry id]

  /// The part a hit or query reports: instance id = object id (0 = static), geometry id.
  const PartData& part(unsigned object_id, unsigned geometry_id) const {
    return object_id == 0 ? static_parts[geometry_id] : object_parts[object_id - 1][geometry_id];
  }
};

/// Builds every scene; Error naming the Embree call on failure.
std::shared_ptr<const SceneAssets> buildSceneAssets(const StaticWorld& static_world,
                                                    const std::vector<ShapeGeometry>& shapes,
                                                    const std::vector<Material>& materials);

}  // namespace strata::sim
