#pragma once
// `strata-bench select`: keyframe selection: keyframes scored per second against a map
// (device time of the sparse raycast, raycast_samples.comp, from timestamp queries) at 640x480,
// with the method's 10 px sample grid and with dense sampling (every pixel), plus the host time of
// the metrics; a self-check compares device and reference hit masks on a few keyframes.
#include <string>

namespace CLI {
class App;
}

namespace strata::bench {

struct SelectBenchOptions {
  std::string world = "room";
  float voxel_size_m = 0.02f;
  int map_frames = 60;   // session 0 keyframes fused into the map
  int keyframes = 30;    // session 1 keyframes scored per sampling
  std::string out_path;  // also write the JSON here (atomically)
  std::string device;
};

CLI::App* addSelectCommand(CLI::App& app, SelectBenchOptions& options);

/// Prints the JSON report; exit code 0, 1 when the self-check failed, 2 bad input, 3 device error.
int runSelectBench(const SelectBenchOptions& options);

}  // namespace strata::bench
