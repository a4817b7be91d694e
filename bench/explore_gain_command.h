#pragma once
// `strata-bench explore-gain`: the view gain kernel (shaders/explore/view_gain.comp): positions
// scored per second on a simulated map (device time from timestamp queries), batches of several
// sizes, and the host reference's time; a self-check requires device and reference results to be
// equal on one batch.
#include <string>
#include <vector>

namespace CLI {
class App;
}

namespace strata::bench {

struct ExploreGainBenchOptions {
  std::string world = "office";
  float voxel_size_m = 0.1f;
  int map_frames = 60;                     // session 0 keyframes fused into the map
  std::vector<int> batches = {100, 1000};  // positions per dispatch
  int repeats = 5;                         // dispatches per batch size (median reported)
  int reference_positions = 100;           // timed on the host and compared with the device
  std::string out_path;                    // also write the JSON here (atomically)
  std::string device;
};

CLI::App* addExploreGainCommand(CLI::App& app, ExploreGainBenchOptions& options);

/// Prints the JSON report; exit code 0, 1 when the self-check failed, 2 bad input, 3 device error.
int runExploreGainBench(const ExploreGainBenchOptions& options);

}  // namespace strata::bench
