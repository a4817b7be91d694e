#pragma once
// `strata-bench posegraph`: the multi-session pose graph (align/pose_graph.h) on a fixed synthetic
// map (align/synthetic_sessions.h): sessions of drifting odometry around overlapping circles, true
// loops within and across sessions plus 20 % false ones; time to place and relax, and accuracy.
#include <string>

namespace CLI {
class App;
}

namespace strata::bench {

struct PoseGraphBenchOptions {
  int sessions = 5;
  int keyframes = 600;   // per session
  int threads = 2;       // Ceres threads
  int repeats = 3;       // the fastest solve is reported
  std::string out_path;  // also write the JSON here (atomically)
};

CLI::App* addPoseGraphCommand(CLI::App& app, PoseGraphBenchOptions& options);

/// Prints the JSON report; exit code 0, 1 when the self-check failed, 2 bad input.
int runPoseGraphBench(const PoseGraphBenchOptions& options);

}  // namespace strata::bench
