#pragma once
// `strata eval-trajectory EST GT`: accuracy of an estimated trajectory against the truth (both
// TUM format, camera-to-world): ATE after alignment and RPE per metre, printed, optionally as a
// JSON report and a top-down plot. The options, then the outputs against both inputs and each
// other are checked before a file is read; an empty trajectory file, or fewer than 3 estimated
// poses with a true pose within --max-dt, is refused (no figures from too few poses).
// Exit 0 on success, 2 on bad input (named), 1 on other errors; a failed run leaves no new JSON
// or plot behind.
#include <string>

namespace CLI {
class App;
}

namespace strata::apps {

struct EvalTrajectoryOptions {
  std::string estimate_path;
  std::string truth_path;
  std::string alignment = "se3";  // none, first, se3, sim3
  double max_time_difference_s = 0.02;
  double rpe_segment_m = 1.0;
  std::string json_path;  // empty: none
  std::string plot_path;  // empty: none; PNG, top-down view of both trajectories
};

CLI::App* addEvalTrajectoryCommand(CLI::App& app, EvalTrajectoryOptions& options);
int runEvalTrajectory(const EvalTrajectoryOptions& options);

}  // namespace strata::apps
