#include "strata/lcm/convert_objects.h"

namespace strata::lcm_io {
namespace {

object_instance_t encodeInstance(const objects::ObjectInstance& instance) {
  object_instance_t m{};
  m.session = instance.session;
  m.segment_id = instance.segment_id;
  const Eigen::Matrix4d T = instance.T_W_M.matrix();
  for (int r = 0; r < 4; ++r) {
    for (int c = 0; c < 4; ++c) m.T_W_M[4 * r + c] = T(r, c);
  }
  m.match_score = static_cast<float>(instance.match_score);
  return m;
}

}  // namespace

object_update_t encodeObjectUpdate(const objects::ObjectModel& model, int session, bool new_model,
                                   int index, int count, std::int64_t utime) {
  object_update_t m{};
  m.utime = utime;
  m.session = session;
  m.update_index = index;
  m.num_updates = count;
  m.model_id = model.id;
  m.new_model = new_model;
  m.merged_observations = model.merged_observations;
  m.surface_area_m2 = model.surface_area_m2;
  for (const objects::ObjectInstance& instance : model.instances) {
    m.instances.push_back(encodeInstance(instance));
  }
  m.num_instances = static_cast<std::int32_t>(m.instances.size());
  const Mesh& mesh = model.mesh_M;
  m.vertices.reserve(mesh.vertices.size());
  for (const Eigen::Vector3f& v : mesh.vertices) m.vertices.push_back({v.x(), v.y(), v.z()});
  m.num_vertices = static_cast<std::int32_t>(m.vertices.size());
  m.triangles.reserve(mesh.triangles.size());
  for (const Eigen::Vector3i& t : mesh.triangles) m.triangles.push_back({t.x(), t.y(), t.z()});
  m.num_triangles = static_cast<std::int32_t>(m.triangles.size());
  return m;
}

}  // namespace strata::lcm_io
