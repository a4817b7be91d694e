#pragma once
// `strata-bench esdf`: ESDF update times at 5 cm on the real sample (redkitchen) and a simulated
// room session: per-frame incremental updates during fusion and full recomputations (device time
// from timestamp queries), updated voxels per second, the C++ reference, planner queries on host
// and device; voxblox's published figure beside them.
#include <string>

namespace CLI {
class App;
}

namespace strata::bench {

struct EsdfBenchOptions {
  std::string data_dir;  // default: the shared redkitchen frames (set by addEsdfCommand)
  std::string world = "room";
  int frames = 150;  // per input (redkitchen has 150)
  float voxel_size_m = 0.05f;
  /// Allocate the observed free space too (MapConfig::allocate_free_space), so the ESDF covers
  /// open space as voxblox's does; off: only the surfaces' truncation band.
  bool free_space = true;
  int query_points = 100000;
  std::string out_path;  // also write the JSON here (atomically)
  std::string device;
};

CLI::App* addEsdfCommand(CLI::App& app, EsdfBenchOptions& options);

/// Prints the JSON report; exit code 0, 1 when a self-check failed, 2 bad input, 3 device error.
int runEsdfBench(const EsdfBenchOptions& options);

}  // namespace strata::bench
