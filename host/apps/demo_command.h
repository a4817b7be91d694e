#pragma once
// `strata demo` (and `strata` with no command): the multi-session demo on a synthetic world:
// simulate every session, fuse each into its own map on the device, write meshes and a report.
#include <cstdint>
#include <string>

namespace CLI {
class App;
}

namespace strata::apps {

struct DemoOptions {
  std::string world;  // "" = the shipped single room
  int sessions = 0;   // 0 = the world's count
  std::string out_dir = "strata_out";
  std::uint64_t seed = 0;
  int frames = 60;    // per session, spread over the path
  float voxel_size_m = 0.02f;
  bool no_noise = false;
  std::string device;
  bool quiet = false;
};

CLI::App* addDemoCommand(CLI::App& app, DemoOptions& options);
int runDemo(const DemoOptions& options);

}  // namespace strata::apps
