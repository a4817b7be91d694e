#pragma once
// `strata-bench vio`: the visual-inertial back end (strata::odometry) on the synthetic stereo +
// IMU room sequence: time per frame (addFrame: preintegration, solve, marginalisation; thread CPU
// time and wall time), the share of the 20 Hz frame period it uses, and the trajectory error.
#include <string>

namespace CLI {
class App;
}

namespace strata::bench {

struct VioBenchOptions {
  int window_size = 10;
  int max_iterations = 6;
  int max_features = 100;     // per frame
  double standstill_s = 1.0;  // 0: start in motion
  int repeats = 3;            // runs of the whole sequence (timing: the fastest in CPU time)
  std::string out_path;       // also write the JSON here (atomically)
};

CLI::App* addVioCommand(CLI::App& app, VioBenchOptions& options);

/// Prints the JSON report; exit code 0, 1 when tracking failed or drifted (ATE over 5 cm),
/// 2 bad input.
int runVioBench(const VioBenchOptions& options);

}  // namespace strata::bench
