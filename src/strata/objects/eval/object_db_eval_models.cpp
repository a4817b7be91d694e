#include "strata/objects/eval/internal/object_db_eval_models.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <set>

#include "strata/sim/world/triangle_distance.h"

namespace strata::eval::detail {
namespace {

/// Distance from p to the nearest triangle of `mesh` (brute force: true meshes have at most a few
/// hundred triangles).
double distanceToMesh(const Eigen::Vector3d& p, const Mesh& mesh) {
  double best = std::numeric_limits<double>::infinity();
  for (const Eigen::Vector3i& t : mesh.triangles) {
    const Eigen::Vector3d q = sim::closestPointOnTriangle(p, mesh.vertices[t[0]].cast<double>(),
                                                          mesh.vertices[t[1]].cast<double>(),
                                                          mesh.vertices[t[2]].cast<double>());
    best = std::min(best, (p - q).squaredNorm());
  }
  return std::sqrt(best);
}

/// Mean distance of the model's vertices at T_W_M to the true mesh at T_W_O.
double instanceAccuracy(const Mesh& mesh_M, const Eigen::Isometry3d& T_W_M,
                        const Eigen::Isometry3d& T_W_O, const Mesh& truth_O,
                        std::size_t max_vertices) {
  const std::size_t n = mesh_M.vertices.size();
  const std::size_t stride = std::max<std::size_t>(1, (n + max_vertices - 1) / max_vertices);
  const Eigen::Isometry3d T_O_M = T_W_O.inverse() * T_W_M;
  double sum = 0.0;
  std::size_t count = 0;
  for (std::size_t i = 0; i < n; i += stride) {
    sum += distanceToMesh(T_O_M * mesh_M.vertices[i].cast<double>(), truth_O);
    ++count;
  }
  return count ? sum / double(count) : 0.0;
}

/// The object most of the model's instances lie on (ties: the smaller id; 0 when none does).
int majorityObject(const objects::ObjectModel& model, const SegmentObjects& segments) {
  std::map<int, int> votes;
  for (const objects::ObjectInstance& instance : model.instances) {
    const int id = instanceObject(segments, instance);
    if (id != 0) ++votes[id];
  }
  int best = 0, best_votes = 0;
  for (const auto& [id, n] : votes) {
    if (n > best_votes) best = id, best_votes = n;
  }
  return best;
}

}  // namespace

int instanceObject(const SegmentObjects& segments, const objects::ObjectInstance& instance) {
  const auto it = segments.find({instance.session, instance.segment_id});
  return it == segments.end() ? 0 : it->second;
}

double triangleArea(const Mesh& mesh, bool skip_floor, double floor_z_m) {
  double area = 0.0;
  for (const Eigen::Vector3i& t : mesh.triangles) {
    const Eigen::Vector3d a = mesh.vertices[t[0]].cast<double>();
    const Eigen::Vector3d b = mesh.vertices[t[1]].cast<double>();
    const Eigen::Vector3d c = mesh.vertices[t[2]].cast<double>();
    if (skip_floor && a.z() <= floor_z_m && b.z() <= floor_z_m && c.z() <= floor_z_m) continue;
    area += 0.5 * (b - a).cross(c - a).norm();
  }
  return area;
}

ModelEvaluation evaluateModel(const objects::ObjectModel& model, const SegmentObjects& segments,
                              const ObjectDbTruth& truth, const ObjectDbEvalConfig& config) {
  ModelEvaluation r;
  r.model_id = model.id;
  r.instances = static_cast<int>(model.instances.size());
  r.area_m2 = model.surface_area_m2 > 0.0f ? double(model.surface_area_m2)
                                           : triangleArea(model.mesh_M, false);
  std::set<int> sessions;
  double accuracy_sum = 0.0;
  for (const objects::ObjectInstance& instance : model.instances) {
    sessions.insert(instance.session);
    r.largest_observation_m2 =
        std::max(r.largest_observation_m2, double(instance.observed_area_m2));
    const int id = instanceObject(segments, instance);
    if (id == 0 || model.mesh_M.vertices.empty()) continue;
    const auto index = static_cast<std::size_t>(id - 1);
    const Eigen::Isometry3d& T_W_O =
        truth.sessions[static_cast<std::size_t>(instance.session)].objects[index].T_W_O;
    accuracy_sum += instanceAccuracy(model.mesh_M, instance.T_W_M, T_W_O, truth.meshes_O[index],
                                     config.max_accuracy_vertices);
    ++r.accuracy_instances;
  }
  r.sessions = static_cast<int>(sessions.size());
  r.completeness = r.largest_observation_m2 > 0.0 ? r.area_m2 / r.largest_observation_m2 : 0.0;
  r.accuracy_m = r.accuracy_instances ? accuracy_sum / r.accuracy_instances : 0.0;
  r.object_id = majorityObject(model, segments);
  if (r.object_id != 0) {
    const auto index = static_cast<std::size_t>(r.object_id - 1);
    r.name = truth.names[index];
    r.true_area_m2 = triangleArea(truth.meshes_O[index], true);
    r.growth = r.true_area_m2 > 0.0 ? r.area_m2 / r.true_area_m2 : 0.0;
  }
  return r;
}

}  // namespace strata::eval::detail
