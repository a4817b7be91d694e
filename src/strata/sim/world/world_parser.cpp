#include "strata/sim/world/world_parser.h"

#include <filesystem>
#include <set>

#include "strata/core/error.h"
#include "strata/sim/world/internal/object_parser.h"
#include "strata/sim/world/internal/yaml_field.h"

namespace strata::sim {
namespace {

const Material kFloor{{150, 140, 125}, 0.0f};
const Material kWalls{{215, 212, 200}, 0.0f};
const Material kCeiling{{235, 235, 235}, 0.0f};

std::string coordinateLimit() {
  return "every coordinate must be within " +
         std::to_string(static_cast<int>(kMaxWorldCoordinateM)) +
         " m of the origin (kMaxWorldCoordinateM)";
}

RoomSpec parseRoom(const YamlField& field, int index) {
  field.allowKeys({"name", "min", "max", "height", "floor", "walls", "ceiling"});
  RoomSpec room;
  room.name = field.has("name") ? field.get("name").text() : "room_" + std::to_string(index);
  const YamlField min = field.get("min");
  room.min_m = min.vec2();
  const YamlField max = field.get("max");
  room.max_m = max.vec2();
  const auto within = [](const Eigen::Vector2d& p) {
    return p.cwiseAbs().maxCoeff() <= kMaxWorldCoordinateM;
  };
  if (!within(room.min_m)) min.fail(coordinateLimit());
  if (!within(room.max_m)) max.fail(coordinateLimit());
  if ((room.max_m.array() <= room.min_m.array()).any()) max.fail("must exceed min in x and y");
  if ((room.max_m - room.min_m).maxCoeff() > kMaxRoomSideM) {
    max.fail("a room side may be at most " + std::to_string(static_cast<int>(kMaxRoomSideM)) +
             " m (kMaxRoomSideM)");
  }
  const YamlField height = field.get("height");
  room.height_m = height.positive();
  if (room.height_m > kMaxRoomHeightM) {
    height.fail("may be at most " + std::to_string(static_cast<int>(kMaxRoomHeightM)) +
                " m (kMaxRoomHeightM)");
  }
  room.floor = field.has("floor") ? parseMaterial(field.get("floor"), kFloor) : kFloor;
  room.walls = field.has("walls") ? parseMaterial(field.get("walls"), kWalls) : kWalls;
  room.ceiling = field.has("ceiling") ? parseMaterial(field.get("ceiling"), kCeiling) : kCeiling;
  return room;
}

DoorSpec parseDoor(const YamlField& field) {
  field.allowKeys({"at", "width", "height"});
  DoorSpec door;
  door.line = field.line();
  door.at_m = field.get("at").vec2();
  door.width_m = field.positiveOr("width", door.width_m);
  door.height_m = field.positiveOr("height", door.height_m);
  return door;
}

RegionSpec parseRegion(const YamlField& field) {
  field.allowKeys({"min", "max"});
  RegionSpec region;
  region.min_m = field.get("min").vec2();
  const YamlField max = field.get("max");
  region.max_m = max.vec2();
  if ((region.max_m.array() <= region.min_m.array()).any()) max.fail("must exceed min in x and y");
  return region;
}

/// The keys shared by `changes` and its per-session overrides, over `rules`.
void parseRuleKeys(const YamlField& field, ChangeRules& rules) {
  rules.move_probability = field.fractionOr("move_probability", rules.move_probability);
  rules.remove_probability = field.fractionOr("remove_probability", rules.remove_probability);
  if (rules.move_probability + rules.remove_probability > 1.0) {
    field.fail("move_probability + remove_probability must not exceed 1");
  }
  if (const auto add = field.find("add")) {
    const std::vector<YamlField> range = add->items();
    if (range.size() != 2) add->fail("expected [min, max] counts");
    rules.add_min = static_cast<int>(range[0].integer(0, 1000));
    rules.add_max = static_cast<int>(range[1].integer(rules.add_min, 1000));
  }
  if (const auto min_changes = field.find("min_changes")) {
    rules.min_changes = static_cast<int>(min_changes->integer(1, 1000));
  }
  if (const auto distance = field.find("min_move_distance")) {
    rules.min_move_distance_m = distance->nonNegative();
  }
}

void parseChanges(const YamlField& field, int session_count, WorldSpec& spec) {
  const std::vector<std::string> rule_keys = {"move_probability", "remove_probability", "add",
                                              "min_changes", "min_move_distance"};
  std::vector<std::string> keys = rule_keys;
  keys.push_back("sessions");
  field.allowKeys(keys);
  parseRuleKeys(field, spec.changes);
  if (!field.has("sessions")) return;
  keys = rule_keys;
  keys.push_back("session");
  for (const YamlField& item : field.get("sessions").items()) {
    item.allowKeys(keys);
    SessionOverride entry{static_cast<int>(item.get("session").integer(1, session_count - 1)),
                          spec.changes};
    parseRuleKeys(item, entry.rules);
    spec.overrides.push_back(entry);
  }
}

void parsePlacement(const YamlField& field, WorldSpec& spec) {
  field.allowKeys({"regions", "clearance", "door_clearance"});
  if (field.has("regions")) {
    for (const YamlField& item : field.get("regions").items()) {
      spec.regions.push_back(parseRegion(item));
    }
  }
  if (field.has("clearance")) spec.clearance_m = field.get("clearance").nonNegative();
  if (field.has("door_clearance"))
    spec.door_clearance_m = field.get("door_clearance").nonNegative();
}

LightingSpec parseLighting(const YamlField& field) {
  field.allowKeys({"direction", "intensity", "ambient", "vary_direction", "vary_intensity"});
  LightingSpec light;
  if (const auto direction = field.find("direction")) {
    light.direction_W = direction->vec3();
    if (light.direction_W.norm() < 1e-9) direction->fail("must not be zero");
  }
  light.direction_W.normalize();
  if (field.has("intensity")) light.intensity = field.get("intensity").nonNegative();
  light.ambient = field.fractionOr("ambient", light.ambient);
  if (field.has("vary_direction"))
    light.vary_direction_deg = field.get("vary_direction").nonNegative();
  light.vary_intensity = field.fractionOr("vary_intensity", light.vary_intensity);
  return light;
}

/// A pillar marked height 0 reaches the ceiling of the room its centre stands in.
void raisePillar(const YamlField& field, const std::vector<RoomSpec>& rooms, ObjectSpec& object) {
  if (object.shape.kind != ShapeKind::kCylinder || object.shape.size_m.z() > 0.0) return;
  for (const RoomSpec& room : rooms) {
    const Eigen::Vector2d& at = *object.at_m;
    if ((at.array() >= room.min_m.array()).all() && (at.array() <= room.max_m.array()).all()) {
      object.shape.size_m.z() = room.height_m;
      return;
    }
  }
  field.fail("a pillar without a height must stand inside a room");
}

void parseObjectList(const YamlField& root, const std::string& key, const ObjectParseContext& ctx,
                     const std::vector<RoomSpec>& rooms, std::vector<ObjectSpec>& out) {
  if (!root.has(key)) return;
  for (const YamlField& item : root.get(key).items()) {
    if (key == "pool" && item.has("at")) {
      item.get("at").fail("pool objects are placed by the seed when they appear; remove 'at'");
    }
    std::optional<ObjectSpec> object = parseObject(item, ctx);
    if (!object) continue;
    if (object->name.empty()) object->name = key + "_" + std::to_string(out.size() + 1);
    if (ctx.is_static) raisePillar(item, rooms, *object);
    out.push_back(std::move(*object));
  }
}

void checkUniqueNames(const YamlField& root, const WorldSpec& spec) {
  std::set<std::string> seen;
  for (const auto* list : {&spec.objects, &spec.pool}) {
    for (const ObjectSpec& object : *list) {
      if (seen.insert(object.name).second) continue;
      throw InputError(spec.source + ":" + std::to_string(object.line) + ": object name '" +
                       object.name + "' used twice (names must be unique)");
    }
  }
  if (spec.objects.empty() && spec.pool.empty()) root.fail("a world needs objects or a pool");
}

WorldSpec parseRoot(const YamlField& root, const std::string& source, const std::string& base_dir) {
  root.allowKeys({"name", "seed", "sessions", "wall_thickness", "rooms", "doors", "static",
                  "objects", "pool", "placement", "changes", "lighting"});
  WorldSpec spec;
  spec.source = source;
  spec.name =
      root.has("name") ? root.get("name").text() : std::filesystem::path(source).stem().string();
  spec.seed = root.has("seed") ? root.get("seed").unsignedInteger() : spec.seed;
  if (root.has("sessions"))
    spec.session_count = static_cast<int>(root.get("sessions").integer(1, 1000));
  spec.wall_thickness_m = root.positiveOr("wall_thickness", spec.wall_thickness_m);
  const std::vector<YamlField> rooms = root.get("rooms").items();
  if (rooms.empty()) root.get("rooms").fail("a world needs at least one room");
  for (std::size_t i = 0; i < rooms.size(); ++i) spec.rooms.push_back(parseRoom(rooms[i], i + 1));
  if (root.has("doors")) {
    for (const YamlField& item : root.get("doors").items()) spec.doors.push_back(parseDoor(item));
  }
  parseObjectList(root, "static", {true, base_dir}, spec.rooms, spec.static_elements);
  parseObjectList(root, "objects", {false, base_dir}, spec.rooms, spec.objects);
  parseObjectList(root, "pool", {false, base_dir}, spec.rooms, spec.pool);
  checkUniqueNames(root, spec);
  if (root.has("placement")) parsePlacement(root.get("placement"), spec);
  if (root.has("changes")) parseChanges(root.get("changes"), spec.session_count, spec);
  if (root.has("lighting")) spec.lighting = parseLighting(root.get("lighting"));
  return spec;
}

}  // namespace

WorldSpec parseWorldSpec(const std::string& text, const std::string& name_for_errors,
                         const std::string& base_dir) {
  YAML::Node document;
  try {
    document = YAML::Load(text);
  } catch (const YAML::Exception& e) {
    throw InputError(name_for_errors + ":" + std::to_string(e.mark.line + 1) +
                     ": YAML syntax error: " + e.msg);
  }
  const YamlField root(document, name_for_errors);
  if (!document.IsMap()) root.fail("a world file is a map of key: value (name, rooms, objects...)");
  return parseRoot(root, name_for_errors, base_dir);
}

}  // namespace strata::sim
