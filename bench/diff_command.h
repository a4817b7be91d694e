#pragma once
// `strata-bench diff`: multi-session change detection on a simulated world's sessions:
// device time per session update and per stage (difference, erosion, dilation, static update,
// the session's dynamic part) and per voxel, from timestamp queries, next to the C++ reference
// on the same session maps; device and reference labels compared (a self-check).
#include <string>

namespace CLI {
class App;
}

namespace strata::bench {

struct DiffBenchOptions {
  std::string world = "room";
  int sessions = 0;  // 0: all of the world's sessions
  float voxel_size_m = 0.02f;
  int frames = 0;          // per session, spread over its path; 0: every frame at 30 Hz
  bool free_space = true;  // MapConfig::allocate_free_space (what ChangeDetector wants)
  bool reference = true;   // also run the C++ reference on the device's session maps
  std::string out_path;    // also write the JSON here (atomically)
  std::string device;      // Vulkan device index or name substring
};

CLI::App* addDiffCommand(CLI::App& app, DiffBenchOptions& options);

/// Prints the JSON report; exit code 0, 1 when a self-check failed, 2 bad input, 3 device error.
int runDiffBench(const DiffBenchOptions& options);

}  // namespace strata::bench
