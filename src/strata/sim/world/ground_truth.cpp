#include "strata/sim/world/ground_truth.h"

#include <charconv>
#include <cstdio>
#include <filesystem>
#include <nlohmann/json.hpp>

#include "strata/core/atomic_file.h"
#include "strata/core/error.h"
#include "strata/mesh/ply.h"
#include "strata/sim/world/shape_mesh.h"

namespace strata::sim {
namespace {

using Json = nlohmann::ordered_json;

/// `value` rounded to 10 significant digits, -0 as 0: the file shows short numbers that do not
/// differ by the last bits of a computation or by the sign of a zero.
double number(double value) {
  if (value == 0.0) return 0.0;
  char text[32];
  const std::to_chars_result end =
      std::to_chars(text, text + sizeof(text), value, std::chars_format::general, 10);
  double rounded = value;
  std::from_chars(text, end.ptr, rounded);
  return rounded;
}

template <typename Vector>
Json array(const Vector& v) {
  Json out = Json::array();
  for (int i = 0; i < static_cast<int>(v.size()); ++i) out.push_back(number(v[i]));
  return out;
}

/// Adds "T_W_O" (4 rows), "position", "quaternion_wxyz" and "yaw_deg" to `json`.
void addPose(const ObjectState& object, Json& json) {
  const Eigen::Matrix4d T = object.T_W_O.matrix();
  Json rows = Json::array();
  for (int r = 0; r < 4; ++r) rows.push_back(array(Eigen::Vector4d(T.row(r).transpose())));
  Eigen::Quaterniond q(object.T_W_O.linear());
  if (q.w() < 0.0) q.coeffs() = -q.coeffs();  // one of the two equal quaternions, always the same
  json["T_W_O"] = std::move(rows);
  json["position"] = array(object.T_W_O.translation());
  json["quaternion_wxyz"] = array(Eigen::Vector4d(q.w(), q.x(), q.y(), q.z()));
  json["yaw_deg"] = number(object.yaw_deg);
}

Json objectJson(const World& world, const ObjectState& object) {
  const ObjectSpec& spec = world.object(object.id);
  const auto& rgb = spec.material.albedo;
  Json json;
  json["id"] = object.id;
  json["name"] = object.name;
  json["shape"] = shapeKindName(object.shape);
  json["present"] = object.present;
  json["changed_since_previous"] = changeName(object.since_previous);
  json["changed_since_first"] = changeName(object.since_first);
  addPose(object, json);
  json["size_m"] = array(spec.shape.size_m);
  json["albedo"] = Json::array({int(rgb[0]), int(rgb[1]), int(rgb[2])});
  json["reflectivity"] = number(spec.material.reflectivity);
  json["mesh"] = "objects/" + objectFileStem(world, object.id) + ".ply";
  return json;
}

void makeDirs(const std::string& dir) {
  std::error_code error;
  std::filesystem::create_directories(dir, error);
  if (error) throw Error("cannot create folder '" + dir + "': " + error.message());
}

}  // namespace

std::string objectFileStem(const World& world, int object_id) {
  char id[16];
  std::snprintf(id, sizeof(id), "%02d", object_id);
  return std::string(id) + "_" + world.object(object_id).name;
}

std::string sessionJson(const World& world, int session) {
  const SessionTruth& truth = world.session(session);
  Json light;
  light["direction_W"] = array(truth.light.direction_W);
  light["intensity"] = number(truth.light.intensity);
  light["ambient"] = number(truth.light.ambient);
  Json objects = Json::array();
  for (const ObjectState& object : truth.objects) objects.push_back(objectJson(world, object));
  Json json;
  json["world"] = world.name();
  json["seed"] = world.seed();
  json["session"] = session;
  json["light"] = std::move(light);
  json["objects"] = std::move(objects);
  return json.dump(2, ' ', false, Json::error_handler_t::replace) + "\n";
}

void writeSessionGroundTruth(const World& world, int session, const std::string& dir) {
  const SessionTruth& truth = world.session(session);
  makeDirs(dir + "/objects");
  writePly(dir + "/world.ply", world.sessionMesh(session));
  for (const ObjectState& object : truth.objects) {
    if (!object.present) continue;
    Mesh placed;
    appendMesh(world.objectMesh(object.id), object.T_W_O, world.object(object.id).material.albedo,
               placed);
    writePly(dir + "/objects/" + objectFileStem(world, object.id) + ".ply", placed);
  }
  writeTextAtomically(dir + "/objects.json", sessionJson(world, session));
}

void writeGroundTruth(const World& world, const std::string& dir) {
  makeDirs(dir + "/objects");
  writePly(dir + "/static.ply", world.staticMesh());
  for (int id = 1; id <= world.objectCount(); ++id) {
    writePly(dir + "/objects/" + objectFileStem(world, id) + ".ply", world.objectMesh(id));
  }
  for (int s = 0; s < world.sessionCount(); ++s) {
    char name[32];
    std::snprintf(name, sizeof(name), "/session_%d", s);
    writeSessionGroundTruth(world, s, dir + name);
  }
}

}  // namespace strata::sim
