#include "strata/lcm/convert_change.h"

namespace strata::lcm_io {

change_event_t encodeChangeEvent(const change::DiscoveredObject& object, int num_objects,
                                 std::int64_t utime) {
  change_event_t event{};
  event.utime = utime;
  event.session = object.session;
  event.object_id = object.id;
  event.num_objects = num_objects;
  for (int a = 0; a < 3; ++a) {
    event.centroid[a] = object.centroid[a];
    event.bbox_min[a] = object.bbox.isEmpty() ? 0.0f : object.bbox.min()[a];
    event.bbox_max[a] = object.bbox.isEmpty() ? 0.0f : object.bbox.max()[a];
  }
  for (const Eigen::Vector3f& v : object.mesh.vertices)
    event.vertices.push_back({v.x(), v.y(), v.z()});
  for (const Eigen::Vector3i& t : object.mesh.triangles) {
    event.triangles.push_back({t.x(), t.y(), t.z()});
  }
  event.num_vertices = static_cast<std::int32_t>(event.vertices.size());
  event.num_triangles = static_cast<std::int32_t>(event.triangles.size());
  return event;
}

}  // namespace strata::lcm_io
