#pragma once
// `strata-bench sim`: rendering speed of the simulated RGB-D camera on every shipped world.
#include <string>
#include <vector>

namespace CLI {
class App;
}

namespace strata::bench {

struct SimBenchOptions {
  std::vector<std::string> worlds = {"room", "office", "warehouse"};
  int frames = 60;  // rendered per world (after warm-up)
  bool noise = true;
  std::string out_path;
};

CLI::App* addSimCommand(CLI::App& app, SimBenchOptions& options);
int runSimBench(const SimBenchOptions& options);

}  // namespace strata::bench
