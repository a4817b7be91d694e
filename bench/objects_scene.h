#pragma once
// Analytic object sessions for `strata-bench objects`: one of the simulator's shapes (box,
// cylinder, chair, table, shelf: sim/world/shape_mesh.h) of a given size and colour standing on a
// floor, turned into a session as change detection would hand it to the object database: a TSDF
// of exact signed distances (2 cm voxels, weight 20 where observed), the shape's voxels labelled
// dynamic, and its objects discovered by change::extractObjects. A view is either complete (every
// side observed, as a model after a few sessions) or half of the shape (the side facing -y of its
// own frame, as one session's segment).
#include <array>
#include <cstdint>
#include <vector>

#include "strata/change/object_discovery.h"
#include "strata/map/tsdf_map.h"
#include "strata/sim/world/world_spec.h"

namespace strata::bench {

struct BenchShape {
  sim::ShapeSpec spec;
  std::array<std::uint8_t, 3> albedo{128, 128, 128};
};

/// `count` shapes of assorted kinds, sizes (0.25 to 1.4 m) and colours; deterministic.
std::vector<BenchShape> benchShapes(int count);

struct ObjectSession {
  TsdfMap map{MapConfig{}};
  change::LabelledSurface surface;
  std::vector<change::DiscoveredObject> segments;  // largest first
};

enum class View { kComplete, kHalf };

/// The session of `shape` standing at the origin turned by `yaw_deg`, seen as `view`.
ObjectSession objectSession(const BenchShape& shape, double yaw_deg, View view, int session);

}  // namespace strata::bench
