#pragma once
// `strata-bench plan-collision`: batched capsule checks of a spherical robot (strata::plan's
// CollisionChecker) on the host ESDF copy and on the device, per batch size, on a simulated
// session's map; and one RRT* query with each checker (time, sphere tests, batches).
#include <string>

namespace CLI {
class App;
}

namespace strata::bench {

struct PlanCollisionBenchOptions {
  std::string world = "room";
  int frames = 450;  // fused frames of session 0 (15 s: the camera crosses the room)
  float voxel_size_m = 0.05f;
  float radius_m = 0.3f;
  float segment_length_m = 1.0f;
  int rrt_iterations = 1000;  // the RRT* query's cap (fixed seed: runs compare)
  std::string out_path;
  std::string device;
};

CLI::App* addPlanCollisionCommand(CLI::App& app, PlanCollisionBenchOptions& options);

/// Prints the JSON report; exit code 0, 1 when a self-check failed, 2 bad input, 3 device error.
int runPlanCollisionBench(const PlanCollisionBenchOptions& options);

}  // namespace strata::bench
