#pragma once
// `strata-bench fuse`: TSDF fusion throughput, memory and output check on real RGB-D frames, for
// the device path, the C++ reference and (with STRATA_WITH_OPEN3D) Open3D's VoxelBlockGrid.
#include <string>
#include <vector>

namespace CLI {
class App;
}

namespace strata::bench {

struct FuseBenchOptions {
  std::string data_dir;  // default: the shared redkitchen frames (set by addFuseCommand)
  std::vector<float> voxel_sizes_m{0.01f, 0.02f, 0.05f};
  int frames = 0;             // 0: all
  int reference_frames = 20;  // the C++ reference is slow; 0 skips it
  std::string out_path;       // also write the JSON here (atomically)
  std::string device;         // Vulkan device index or name substring
  int prefill_blocks = 0;     // unobserved blocks far away, loaded before the frames
};

/// Registers `fuse` on `app`; the options are filled when it parses.
CLI::App* addFuseCommand(CLI::App& app, FuseBenchOptions& options);

/// Runs the benchmark, prints the JSON report to stdout; returns the process exit code
/// (0, 1 when a self-check failed, 2 bad input, 3 device error).
int runFuseBench(const FuseBenchOptions& options);

}  // namespace strata::bench
