#pragma once
// The files of `strata topo`: the map as JSON and the picture from above.
#include <string>

#include "strata/plan/topo_map.h"

namespace strata::apps {

/// Bytes grid A* keeps for the same bounds and robot (grid_astar.h: kGridAStarBytesPerCell per
/// cell).
std::size_t gridMemoryBytes(const plan::TopoMap& topo);

/// Atomically. Boxes and portal rectangles in metres (world frame); edges as portal pairs with
/// their straight-line length.
void writeTopoJson(const std::string& path, const plan::TopoMap& topo);

/// The clusters at height z_m (NaN: the layer with the most traversable voxels) from above, each
/// in its own colour, voxels no cluster holds dark grey, portals crossing that layer as white
/// lines. Returns the height drawn.
float writeTopoPng(const std::string& path, const plan::TopoMap& topo, float z_m);

}  // namespace strata::apps
