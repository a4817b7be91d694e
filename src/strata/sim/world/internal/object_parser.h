#pragma once
// Parsing of one object entry (static element or movable object) of a world file (internal to the
// world parser; see world_parser.h for the format).
#include <optional>
#include <string>

#include "strata/sim/world/world_spec.h"
#include "strata/sim/world/internal/yaml_field.h"

namespace strata::sim {

struct ObjectParseContext {
  bool is_static = false;  // static elements need `at` and may be pillars
  std::string base_dir;    // relative mesh paths resolve here
};

/// nullopt when an optional mesh file is missing (a warning is printed). A pillar without a height
/// gets size_m.z() = 0: the caller raises it to the ceiling of its room.
std::optional<ObjectSpec> parseObject(const YamlField& field, const ObjectParseContext& context);

/// {albedo: [r, g, b], reflectivity: r}, both optional, over `fallback`.
Material parseMaterial(const YamlField& field, const Material& fallback);

}  // namespace strata::sim
