#pragma once
// `strata plan MAP --from X,Y,Z --to X,Y,Z [--planner grid|topo|rrt] [--radius 0.3]
// [--unknown occupied|free] [--esdf-max-distance 2.0] --out DIR`: load a saved map, compute its
// ESDF, plan a path for a spherical robot, write DIR/path.csv (x,y,z per waypoint, metres, world
// frame), DIR/report.json and DIR/path.png (the path over the ESDF slice at its mean height).
// Options and the outputs against the map are checked before the map is read, the map on the
// host before the device is opened; a failed write leaves none of the files.
#include <string>

namespace CLI {
class App;
}

namespace strata::apps {

struct PlanOptions {
  std::string map_path;
  std::string from;  // "x,y,z"
  std::string to;
  std::string planner = "grid";
  float radius_m = 0.3f;
  std::string unknown = "occupied";
  float esdf_max_distance_m = 2.0f;
  std::string out_dir;
  std::string device;
};

CLI::App* addPlanCommand(CLI::App& app, PlanOptions& options);

/// Returns the exit code: 0 a path was found, 1 no path (the outputs say why) or another error,
/// 2 bad input naming the problem (missing or corrupt map, bad point, start or goal outside the
/// map or in collision, unknown planner), 3 device error.
int runPlan(const PlanOptions& options);

}  // namespace strata::apps
