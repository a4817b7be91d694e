#include "strata/change/eval/evaluation_truth.h"

#include <algorithm>

namespace strata::change {
namespace {

bool samePlace(const sim::ObjectState& a, const sim::ObjectState& b) {
  if (a.present != b.present) return false;
  return !a.present || a.T_W_O.matrix().isApprox(b.T_W_O.matrix(), 1e-9);
}

bool changes(const sim::World& world, int object_id) {
  const sim::ObjectState& first = world.session(0).objects[static_cast<std::size_t>(object_id - 1)];
  for (int s = 1; s < world.sessionCount(); ++s) {
    if (!samePlace(first, world.session(s).objects[static_cast<std::size_t>(object_id - 1)])) {
      return true;
    }
  }
  return false;
}

void appendMesh(const Mesh& part, Mesh& out) {
  const int offset = static_cast<int>(out.vertices.size());
  out.vertices.insert(out.vertices.end(), part.vertices.begin(), part.vertices.end());
  for (const Eigen::Vector3i& t : part.triangles) {
    out.triangles.push_back(t + Eigen::Vector3i::Constant(offset));
  }
}

}  // namespace

std::vector<int> movedObjectIds(const sim::World& world, int session, MovedReference reference) {
  const auto& objects = world.session(session).objects;
  const int last = reference == MovedReference::kAllSessions ? world.sessionCount() : session;
  std::vector<int> ids;
  for (const sim::ObjectState& object : objects) {
    if (!object.present) continue;
    for (int s = 0; s < last; ++s) {
      if (s != session &&
          !samePlace(object, world.session(s).objects[static_cast<std::size_t>(object.id - 1)])) {
        ids.push_back(object.id);
        break;
      }
    }
  }
  return ids;
}

std::vector<int> changingObjectIds(const sim::World& world) {
  std::vector<int> ids;
  for (int id = 1; id <= world.objectCount(); ++id) {
    if (changes(world, id)) ids.push_back(id);
  }
  return ids;
}

Mesh objectMeshInSession(const sim::World& world, int object_id, int session) {
  Mesh mesh = world.objectMesh(object_id);
  const Eigen::Isometry3f T_W_O =
      world.session(session).objects[static_cast<std::size_t>(object_id - 1)].T_W_O.cast<float>();
  for (Eigen::Vector3f& v : mesh.vertices) v = T_W_O * v;
  for (Eigen::Vector3f& n : mesh.normals) n = T_W_O.linear() * n;
  return mesh;
}

std::vector<TruthObject> sessionTruthObjects(const sim::World& world, int session,
                                             const std::vector<int>& moved_ids,
                                             const VisibleSurface& seen, int min_views) {
  std::vector<TruthObject> truth;
  for (const sim::ObjectState& state : world.session(session).objects) {
    if (!state.present) continue;
    TruthObject object;
    object.id = state.id;
    object.name = state.name;
    object.moved = std::find(moved_ids.begin(), moved_ids.end(), state.id) != moved_ids.end();
    object.mesh = objectMeshInSession(world, state.id, session);
    object.visible_points = seen.points(state.id, min_views);
    object.visible_area_m2 =
        static_cast<float>(object.visible_points.size()) * seen.spacing() * seen.spacing();
    truth.push_back(std::move(object));
  }
  return truth;
}

Mesh staticTruthMesh(const sim::World& world) {
  Mesh mesh = world.staticMesh();
  mesh.normals.clear();
  mesh.colors.clear();
  for (int id = 1; id <= world.objectCount(); ++id) {
    if (!changes(world, id) && world.session(0).objects[static_cast<std::size_t>(id - 1)].present) {
      appendMesh(objectMeshInSession(world, id, 0), mesh);
    }
  }
  return mesh;
}

std::vector<Mesh> movedTruthMeshes(const sim::World& world) {
  std::vector<Mesh> meshes;
  for (const int id : changingObjectIds(world)) {
    for (int s = 0; s < world.sessionCount(); ++s) {
      if (world.session(s).objects[static_cast<std::size_t>(id - 1)].present) {
        meshes.push_back(objectMeshInSession(world, id, s));
      }
    }
  }
  return meshes;
}

std::vector<Eigen::Vector3f> seenStaticPoints(const sim::World& world,
                                              const std::vector<const VisibleSurface*>& seen,
                                              int min_views) {
  if (seen.empty()) return {};
  const std::vector<int> changing = changingObjectIds(world);
  VisibleSurface merged(seen.front()->spacing());
  for (const VisibleSurface* surface : seen) {
    for (const int id : surface->objectIds()) {
      if (std::find(changing.begin(), changing.end(), id) != changing.end()) continue;
      for (const Eigen::Vector3f& p : surface->points(id, min_views)) merged.addPoint(0, p);
    }
  }
  return merged.points(0);
}

}  // namespace strata::change
