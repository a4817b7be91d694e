#pragma once
// `strata-bench track`: RGB-D tracking on real frames without their poses — Strata's
// frame-to-model ICP on the device (tracking then fusion per frame) against Open3D's RGB-D
// odometry (frame to frame, hybrid Jacobian, default pyramid) when built with STRATA_WITH_OPEN3D:
// ATE against the dataset's poses and milliseconds per frame for both, and their ratios.
#include <string>
#include <vector>

namespace CLI {
class App;
}

namespace strata::bench {

struct TrackBenchOptions {
  std::string data_dir;  // default: the shared redkitchen frames (set by addTrackCommand)
  int frames = 100;
  std::string out_path;  // also write the JSON here (atomically)
  std::string device;    // Vulkan device index or name substring
  // Tracker settings to compare (defaults: TrackConfig's).
  int model_level = -1;             // -1: the default
  std::vector<int> iterations;      // empty: the default
  double color_weight = -1.0;       // < 0: the default (0: geometry alone)
  bool no_peer = false;             // skip Open3D's odometry (where built with it)
};

CLI::App* addTrackCommand(CLI::App& app, TrackBenchOptions& options);

/// Runs the benchmark, prints the JSON report; returns the exit code (0, 1 when a self-check
/// failed, 2 bad input, 3 device error).
int runTrackBench(const TrackBenchOptions& options);

}  // namespace strata::bench
