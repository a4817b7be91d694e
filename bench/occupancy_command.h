#pragma once
// `strata-bench occupancy`: the OctoMap-style occupancy layer on the analytic scene
// (exact depth) and a simulated room session (sensor noise): update time per frame on the device
// and of the C++ reference, TSDF fusion time beside it, and both representations against the true
// scene (surface position error, completeness).
#include <string>

namespace CLI {
class App;
}

namespace strata::bench {

struct OccupancyBenchOptions {
  std::string world = "room";
  int frames = 30;  // per scene
  float voxel_size_m = 0.05f;
  unsigned pixel_stride = 1;  // OccupancyConfig::pixel_stride (1 = every pixel, as OctoMap)
  std::string out_path;       // also write the JSON here (atomically)
  std::string ply_dir;        // also write occupancy cubes and TSDF meshes (PLY) here
  std::string device;
};

CLI::App* addOccupancyCommand(CLI::App& app, OccupancyBenchOptions& options);

/// Prints the JSON report; exit code 0, 1 when a self-check failed, 2 bad input, 3 device error.
int runOccupancyBench(const OccupancyBenchOptions& options);

}  // namespace strata::bench
