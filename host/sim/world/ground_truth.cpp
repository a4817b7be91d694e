#include "sim/world/ground_truth.h"

#include <cstdio>
#include <filesystem>

#include "core/atomic_file.h"
#include "core/error.h"
#include "core/json_text.h"
#include "mesh/ply.h"
#include "sim/world/shape_mesh.h"

namespace strata::sim {
namespace {

/// Shortest text that reads back to the same float-ish value; -0 printed as 0 so that files do not
/// differ by the sign of a zero.
std::string number(double value) {
  if (value == 0.0) value = 0.0;
  char text[32];
  std::snprintf(text, sizeof(text), "%.10g", value);
  return text;
}


template <typename Vector>
std::string array(const Vector& v) {
  std::string out = "[";
  for (int i = 0; i < static_cast<int>(v.size()); ++i) out += (i ? ", " : "") + number(v[i]);
  return out + "]";
}

std::string poseJson(const ObjectState& object) {
  const Eigen::Matrix4d T = object.T_W_O.matrix();
  std::string rows;
  for (int r = 0; r < 4; ++r) {
    rows += (r ? ", " : "") + array(Eigen::Vector4d(T.row(r).transpose()));
  }
  Eigen::Quaterniond q(object.T_W_O.linear());
  if (q.w() < 0.0) q.coeffs() = -q.coeffs();  // one of the two equal quaternions, always the same
  return "\"T_W_O\": [" + rows + "], \"position\": " + array(object.T_W_O.translation()) +
         ", \"quaternion_wxyz\": " + array(Eigen::Vector4d(q.w(), q.x(), q.y(), q.z())) +
         ", \"yaw_deg\": " + number(object.yaw_deg);
}

std::string objectJson(const World& world, const ObjectState& object) {
  const ObjectSpec& spec = world.object(object.id);
  const auto& rgb = spec.material.albedo;
  return "    {\"id\": " + std::to_string(object.id) + ", \"name\": " + jsonQuoted(object.name) +
         ", \"shape\": " + jsonQuoted(shapeKindName(object.shape)) +
         ", \"present\": " + (object.present ? "true" : "false") +
         ", \"changed_since_previous\": " + jsonQuoted(changeName(object.since_previous)) +
         ", \"changed_since_first\": " + jsonQuoted(changeName(object.since_first)) + ",\n     " +
         poseJson(object) + ",\n     \"size_m\": " + array(spec.shape.size_m) + ", \"albedo\": [" +
         std::to_string(rgb[0]) + ", " + std::to_string(rgb[1]) + ", " + std::to_string(rgb[2]) +
         "], \"reflectivity\": " + number(spec.material.reflectivity) +
         ", \"mesh\": " + jsonQuoted("objects/" + objectFileStem(world, object.id) + ".ply") + "}";
}

void writeText(const std::string& path, const std::string& text) {
  writeFileAtomically(path, std::vector<std::uint8_t>(text.begin(), text.end()));
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
  std::string json = "{\n  \"world\": " + jsonQuoted(world.name()) +
                     ",\n  \"seed\": " + std::to_string(world.seed()) +
                     ",\n  \"session\": " + std::to_string(session) +
                     ",\n  \"light\": {\"direction_W\": " + array(truth.light.direction_W) +
                     ", \"intensity\": " + number(truth.light.intensity) +
                     ", \"ambient\": " + number(truth.light.ambient) + "},\n  \"objects\": [\n";
  for (std::size_t i = 0; i < truth.objects.size(); ++i) {
    json += objectJson(world, truth.objects[i]) + (i + 1 < truth.objects.size() ? ",\n" : "\n");
  }
  return json + "  ]\n}\n";
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
  writeText(dir + "/objects.json", sessionJson(world, session));
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
