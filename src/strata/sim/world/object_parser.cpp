#include "strata/sim/world/internal/object_parser.h"

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <iostream>
#include <map>

#include "strata/sim/world/world_paths.h"

namespace strata::sim {
namespace {

struct TypeInfo {
  ShapeKind kind;
  std::vector<std::string> keys;   // shape keys this type reads
  Eigen::Vector3d default_size_m;  // zero: `size` is required
};

const std::map<std::string, TypeInfo>& typeTable() {
  static const std::map<std::string, TypeInfo> table = {
      {"box", {ShapeKind::kBox, {"size"}, Eigen::Vector3d::Zero()}},
      {"cylinder",
       {ShapeKind::kCylinder, {"radius", "height", "segments"}, Eigen::Vector3d::Zero()}},
      {"pillar", {ShapeKind::kCylinder, {"radius", "height", "segments"}, Eigen::Vector3d::Zero()}},
      {"chair", {ShapeKind::kChair, {"size"}, {0.45, 0.45, 0.9}}},
      {"table", {ShapeKind::kTable, {"size"}, {1.2, 0.8, 0.75}}},
      {"shelf", {ShapeKind::kShelf, {"size", "levels"}, {1.0, 0.4, 1.8}}},
      {"mesh", {ShapeKind::kMesh, {"file", "scale", "up", "optional"}, Eigen::Vector3d::Zero()}},
      {"vase", {ShapeKind::kVase, {"size", "seed"}, {0.35, 0.35, 0.6}}},
      {"blob", {ShapeKind::kBlob, {"size", "seed"}, {0.5, 0.4, 0.45}}},
      {"tube", {ShapeKind::kTube, {"size", "seed"}, {0.6, 0.6, 0.5}}},
      {"l_shape", {ShapeKind::kLShape, {"size", "thickness"}, {0.8, 0.6, 0.7}}},
      {"u_shape", {ShapeKind::kUShape, {"size", "thickness"}, {0.9, 0.6, 0.6}}},
      {"stool", {ShapeKind::kStool, {"size", "legs"}, {0.4, 0.4, 0.65}}},
  };
  return table;
}

const TypeInfo& lookupType(const YamlField& field, bool is_static) {
  const std::string type = field.text();
  const auto it = typeTable().find(type);
  if (it == typeTable().end() || (type == "pillar" && !is_static)) {
    field.fail("unknown type '" + type + "' (expected one of box, cylinder, chair, table, shelf, " +
               "mesh, vase, blob, tube, l_shape, u_shape, stool" + (is_static ? ", pillar)" : ")"));
  }
  return it->second;
}

Eigen::Vector3d parseSize(const YamlField& field) {
  const Eigen::Vector3d size = field.vec3();
  if ((size.array() <= 0.0).any()) field.fail("every size must be positive");
  return size;
}

void parseCylinder(const YamlField& field, const std::string& type, ShapeSpec& shape) {
  shape.radius_m = field.get("radius").positive();
  // A pillar without a height reaches the ceiling: marked 0 here, raised by the caller.
  const double height =
      (type == "pillar") ? field.positiveOr("height", 0.0) : field.get("height").positive();
  shape.size_m = Eigen::Vector3d(2 * shape.radius_m, 2 * shape.radius_m, height);
  if (field.has("segments"))
    shape.segments = static_cast<int>(field.get("segments").integer(6, 1024));
}

/// False when the file is missing and the object is optional.
bool parseMesh(const YamlField& field, const ObjectParseContext& context, ShapeSpec& shape,
               bool& optional) {
  const YamlField file = field.get("file");
  shape.mesh_path = resolveMeshPath(file.text(), context.base_dir);
  shape.scale = field.positiveOr("scale", 1.0);
  optional = field.booleanOr("optional", false);
  if (field.has("up")) {
    const YamlField up = field.get("up");
    if (up.text() != "y" && up.text() != "z") up.fail("expected y or z, got '" + up.text() + "'");
    shape.y_up = up.text() == "y";
  }
  if (std::filesystem::is_regular_file(shape.mesh_path)) return true;
  if (!optional) file.fail("mesh file '" + shape.mesh_path + "' not found");
  std::cerr << "warning: " << field.where() << ": optional mesh '" << shape.mesh_path
            << "' not found; object skipped\n";
  return false;
}

void parseShapeKeys(const YamlField& field, const std::string& type, const TypeInfo& info,
                    ShapeSpec& shape) {
  shape.kind = info.kind;
  if (info.kind == ShapeKind::kCylinder) return parseCylinder(field, type, shape);
  if (info.kind == ShapeKind::kMesh) return;
  if (info.default_size_m.isZero()) {
    shape.size_m = parseSize(field.get("size"));
  } else {
    shape.size_m = field.has("size") ? parseSize(field.get("size")) : info.default_size_m;
  }
  if (field.has("levels")) shape.levels = static_cast<int>(field.get("levels").integer(2, 20));
  if (field.has("seed")) shape.seed = field.get("seed").unsignedInteger();
  if (field.has("legs")) shape.legs = static_cast<int>(field.get("legs").integer(3, 8));
  if (field.has("thickness")) {
    const YamlField thickness = field.get("thickness");
    shape.thickness_m = thickness.positive();
    const double limit = info.kind == ShapeKind::kUShape
                             ? std::min(shape.size_m.x() / 2, shape.size_m.y())
                             : std::min(shape.size_m.x(), shape.size_m.y());
    if (shape.thickness_m >= limit) {
      thickness.fail("must be below " + std::to_string(limit) + " m for this footprint");
    }
  }
}

bool validName(const std::string& name) {
  if (name.empty()) return false;
  for (const char c : name) {
    if (!std::isalnum(static_cast<unsigned char>(c)) && c != '_' && c != '-' && c != '.') {
      return false;
    }
  }
  return true;
}

Material readMaterialKeys(const YamlField& field, const Material& fallback) {
  Material material = fallback;
  if (field.has("albedo")) material.albedo = field.get("albedo").rgb();
  material.reflectivity =
      static_cast<float>(field.fractionOr("reflectivity", fallback.reflectivity));
  return material;
}

}  // namespace

Material parseMaterial(const YamlField& field, const Material& fallback) {
  field.allowKeys({"albedo", "reflectivity"});
  return readMaterialKeys(field, fallback);
}

std::optional<ObjectSpec> parseObject(const YamlField& field, const ObjectParseContext& context) {
  field.expectMap();
  const YamlField type_field = field.get("type");
  const std::string type = type_field.text();
  const TypeInfo& info = lookupType(type_field, context.is_static);
  std::vector<std::string> keys = {"name", "type", "albedo", "reflectivity", "at", "yaw"};
  keys.insert(keys.end(), info.keys.begin(), info.keys.end());
  field.allowKeys(keys);

  ObjectSpec object;
  object.line = field.line();
  object.name = field.has("name") ? field.get("name").text() : "";
  if (field.has("name") && !validName(object.name)) {
    field.get("name").fail("names use letters, digits, '_', '-' and '.' only (they name files)");
  }
  parseShapeKeys(field, type, info, object.shape);
  if (info.kind == ShapeKind::kMesh && !parseMesh(field, context, object.shape, object.optional)) {
    return std::nullopt;
  }
  object.material = readMaterialKeys(field, Material{});
  if (context.is_static || field.has("at")) object.at_m = field.get("at").vec2();
  object.yaw_deg = field.numberOr("yaw", 0.0);
  return object;
}

}  // namespace strata::sim
