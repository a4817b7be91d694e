#pragma once
// `strata sim [WORLD] --sessions N --out DIR`: render every session of a world to disk in the TUM
// RGB-D layout, with the ground truth (meshes, object poses, changes) and IMU in the EuRoC layout.
#include <cstdint>
#include <string>

namespace CLI {
class App;
}

namespace strata::apps {

struct SimOptions {
  std::string world;  // "" = the shipped single room
  int sessions = 0;   // 0 = the world file's count
  std::string out_dir = "strata_sim";
  std::uint64_t seed = 0;  // 0 = the world file's seed
  int max_frames = 0;      // per session, 0 = every frame at --rate
  double rate_hz = 30.0;
  bool no_noise = false;
  bool drift = false;
  bool quiet = false;
};

CLI::App* addSimCommand(CLI::App& app, SimOptions& options);
int runSim(const SimOptions& options);

}  // namespace strata::apps
