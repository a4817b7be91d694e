#pragma once
// `strata odometry SESSION_DIR --mode vio [--mono] --out trajectory.txt`: visual-inertial
// odometry over an EuRoC/ASL session folder (grey stereo or mono + IMU; `strata sim --stereo`
// writes them). Writes the left camera's trajectory in TUM format (timestamp tx ty tz qx qy qz qw,
// camera-to-world, like groundtruth.txt; tracked frames only) and a JSON summary: frames tracked,
// failures with their reasons, speed, and, when the session has ground truth, ATE/RPE after
// SE(3) (and Sim(3)) alignment, the drift from the first pose and the gravity direction error.
// Stereo unless --mono: a session without cam1 is refused (exit 2), not run as mono.
// Before anything is read, the options are checked and every output (trajectory, summary, plot,
// frames CSV) against the session's mav0/ and groundtruth_body.txt and against each other (the
// default summary name included: --out t.json would be its own summary).
// Exit 0 on success, 2 on bad input (named), 3 when no frame was ever tracked or the estimate
// diverged (a pose not finite): then no trajectory or plot is written, only the summary with the
// failures (and the frames CSV when asked); 1 otherwise. A run that fails part-way through its
// writes removes the outputs it had newly made.
#include <string>

namespace CLI {
class App;
}

namespace strata::apps {

struct OdometryOptions {
  std::string session_dir;
  std::string mode = "vio";
  bool mono = false;
  std::string out_path = "trajectory.txt";
  std::string summary_path;     // empty: <out without extension>.json
  std::string plot_path;        // empty: none; top-down PNG against the truth
  std::string frames_csv_path;  // empty: none; one row per processed frame
  /// Anchor the world frame at the true body pose when tracking starts (yaw and position from
  /// the truth; the sessions of a multi-session map then share the truth's frame).
  bool anchor_to_truth = false;
  int window = 10;
  int max_features = 0;  // 0: the front end's default
  int frames = 0;        // 0: all
  bool quiet = false;
  bool solver_log = false;  // the solver's own log on stderr (odometry/solver_log.h)
};

CLI::App* addOdometryCommand(CLI::App& app, OdometryOptions& options);
int runOdometry(const OdometryOptions& options);

}  // namespace strata::apps
