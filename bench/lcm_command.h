#pragma once
// `strata-bench lcm`: end-to-end over LCM for 640x480 RGB-D: frames per second and latency from
// publishing a frame to receiving the mesh update that contains it. The mapper (the same
// MapperCore/MapperNode as strata-mapper) runs in this process on its own threads; frames and
// mesh updates go through LCM on --url (memq:// in-process by default; a udpm:// URL with ttl=0
// sends them through the kernel's loopback multicast, e.g. inside `unshare --net`).
#include <string>

namespace CLI {
class App;
}

namespace strata::bench {

struct LcmBenchOptions {
  std::string url = "memq://";
  int frames = 60;             // of the room's session 0, rendered before timing
  float voxel_size_m = 0.05f;  // strata-mapper's default
  std::string depth_encoding = "depth16";
  bool change_detection = false;  // strata-mapper's default is on: --change to include it
  std::string out_path;           // also write the JSON here (atomically)
  std::string device;
};

CLI::App* addLcmCommand(CLI::App& app, LcmBenchOptions& options);

/// Prints the JSON report; exit code 0, 1 when a self-check failed, 2 bad input, 3 device error.
int runLcmBench(const LcmBenchOptions& options);

}  // namespace strata::bench
