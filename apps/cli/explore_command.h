#pragma once
// `strata explore WORLD.yaml [--planner history|nbvp] [--compare] [--seed N] [--time-limit S]
// [--voxel M] [--start X,Y,Z] [--start-yaw DEG] --out DIR`: closed-loop exploration of session 0 of
// a simulated world (explore/exploration_loop.h) with the history-aware planner, the NBVP baseline,
// or both. Writes per planner DIR/<planner>/{curve.csv, path.png, map.strata, mesh.ply}, and
// DIR/curve.png (explored share vs simulated time) and DIR/report.json. Progress on stderr.
// Options and the outputs against the world file are checked before it is read; a failed run
// leaves none of its files (nor the folders it made).
#include <string>

namespace CLI {
class App;
}

namespace strata::apps {

struct ExploreOptions {
  std::string world_path;
  std::string planner = "history";  // "history" or "nbvp"
  bool compare = false;             // both planners
  unsigned long long seed = 1;      // planners' sampling and the camera's noise
  double time_limit_s = 600.0;      // simulated
  float voxel_size_m = 0.0f;  // 0: explore::defaultVoxelSize of the world
  std::string start;           // "X,Y,Z" metres; "" = defaultStart of the world
  double start_yaw_deg = 0.0;  // heading at the start, about world z from +x
  std::string dead_end;  // "X0,Y0,X1,Y1" metres: a dead end from above to time the escape from
  std::string dead_end_mouth;    // "X,Y" metres: where it opens; "" = its point nearest the start
  std::string tree_box;  // "X,Y,Z" half extents of the local tree's box, metres; "" = default
  int camera_width_px = 160;
  int camera_height_px = 120;
  double eval_period_s = 5.0;
  std::string out_dir;
  std::string device;
  bool quiet = false;
};

CLI::App* addExploreCommand(CLI::App& app, ExploreOptions& options);

/// Returns the exit code: 0 ok, 1 error, 2 bad input (naming the problem), 3 device error.
int runExplore(const ExploreOptions& options);

}  // namespace strata::apps
