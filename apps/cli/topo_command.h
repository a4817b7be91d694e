#pragma once
// `strata topo MAP --out DIR [--radius 0.3] [--unknown occupied|free] [--esdf-max-distance 2.0]
// [--slice-z Z]`: load a saved map, compute its ESDF, build the topological map
// (plan/topo_map.h) and write DIR/topo.json (clusters with their boxes, portals, edges, build
// time, memory against a grid's) and DIR/topo.png (the clusters seen from above at one height,
// each in its own colour, portals marked). Options and the outputs against the map are checked
// before the map is read; a failed write leaves none of the files.
#include <cmath>
#include <string>

namespace CLI {
class App;
}

namespace strata::apps {

struct TopoOptions {
  std::string map_path;
  float radius_m = 0.3f;
  std::string unknown = "occupied";
  float esdf_max_distance_m = 2.0f;
  /// Height of the picture (metres); NaN: the layer with the most traversable voxels.
  float slice_z_m = NAN;
  std::string out_dir;
  std::string device;
};

CLI::App* addTopoCommand(CLI::App& app, TopoOptions& options);

/// Returns the exit code: 0 done, 1 other error, 2 bad input naming the problem, 3 device error.
int runTopo(const TopoOptions& options);

}  // namespace strata::apps
