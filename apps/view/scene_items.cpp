#include "view/scene_items.h"

#include <cmath>

namespace strata::view {
namespace {

nlohmann::json vec3(const Eigen::Vector3f& v) { return {v.x(), v.y(), v.z()}; }

}  // namespace

Message meshMessage(const std::string& id, const std::string& group, const Mesh& mesh, int session,
                    const std::string& label, std::int64_t t_pub_us) {
  nlohmann::json header = {{"type", "mesh"}, {"id", id}, {"group", group}};
  if (t_pub_us > 0) header["t_pub_us"] = t_pub_us;
  if (session >= 0) header["session"] = session;
  if (!label.empty()) header["label"] = label;
  static_assert(sizeof(Eigen::Vector3f) == 12 && sizeof(Eigen::Vector3i) == 12, "packed vectors");
  std::vector<WireArray> arrays = {
      {"positions", WireArray::Type::kF32, mesh.vertices.data(), 3 * mesh.vertices.size()},
      {"indices", WireArray::Type::kU32, mesh.triangles.data(), 3 * mesh.triangles.size()}};
  if (mesh.hasColors() && mesh.colors.size() == mesh.vertices.size()) {
    arrays.push_back({"colors", WireArray::Type::kU8, mesh.colors.data(), 3 * mesh.colors.size()});
  }
  return encodeMessage(std::move(header), arrays);
}

Message objectsMessage(const std::vector<ObjectBox>& objects) {
  nlohmann::json items = nlohmann::json::array();
  for (const ObjectBox& o : objects) {
    nlohmann::json item = {{"id", o.id}, {"min", vec3(o.min_W)}, {"max", vec3(o.max_W)},
                           {"color", {o.color[0], o.color[1], o.color[2]}}};
    if (o.session >= 0) item["session"] = o.session;
    if (!o.label.empty()) item["label"] = o.label;
    items.push_back(std::move(item));
  }
  return encodeMessage({{"type", "objects"}, {"items", std::move(items)}});
}

Message poseMessage(const std::string& id, const Eigen::Isometry3d& T_W_C, double timestamp_s,
                    const std::optional<std::array<double, 6>>& intrinsics,
                    std::int64_t t_pub_us) {
  nlohmann::json T = nlohmann::json::array();
  for (int r = 0; r < 4; ++r) {
    for (int c = 0; c < 4; ++c) T.push_back(T_W_C.matrix()(r, c));
  }
  nlohmann::json header = {{"type", "pose"}, {"id", id}, {"T_W_C", T}, {"t", timestamp_s}};
  if (t_pub_us > 0) header["t_pub_us"] = t_pub_us;
  if (intrinsics) {
    const auto& k = *intrinsics;
    header["intrinsics"] = {{"width", k[0]}, {"height", k[1]}, {"fx", k[2]},
                            {"fy", k[3]},    {"cx", k[4]},     {"cy", k[5]}};
  }
  return encodeMessage(std::move(header));
}

Message polylineMessage(const std::string& type, const std::string& id,
                        const std::vector<Eigen::Vector3f>& points_W) {
  return encodeMessage({{"type", type}, {"id", id}},
                       {{"points", WireArray::Type::kF32, points_W.data(), 3 * points_W.size()}});
}

Message esdfSliceMessage(const EsdfSliceImage& s) {
  nlohmann::json header = {{"type", "esdf_slice"},   {"z", s.z_m},
                           {"origin", {s.origin_x_m, s.origin_y_m}},
                           {"resolution", s.resolution_m}, {"width", s.width},
                           {"height", s.height},     {"max", s.max_m}};
  return encodeMessage(std::move(header),
                       {{"distances", WireArray::Type::kF32, s.distances_m.data(), s.distances_m.size()}});
}

Message answerMessage(int id, const Eigen::Vector3f& point_W, bool known, float distance_m) {
  nlohmann::json header = {{"type", "answer"}, {"id", id}, {"point", vec3(point_W)}, {"known", known}};
  header["distance"] = known && std::isfinite(distance_m) ? distance_m : 0.0f;
  return encodeMessage(std::move(header));
}

}  // namespace strata::view
