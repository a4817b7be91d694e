#include "cli/eval_trajectory_command.h"

#include <CLI/CLI.hpp>
#include <cstdio>

#include "cli/trajectory_plot.h"
#include "strata/core/atomic_file.h"
#include "strata/core/error.h"
#include "strata/trajectory/trajectory_error.h"

namespace strata::apps {

CLI::App* addEvalTrajectoryCommand(CLI::App& app, EvalTrajectoryOptions& o) {
  CLI::App* cmd = app.add_subcommand(
      "eval-trajectory", "Trajectory accuracy: ATE after alignment and RPE per metre (TUM files)");
  cmd->add_option("estimate", o.estimate_path, "Estimated trajectory (TUM format)")->required();
  cmd->add_option("truth", o.truth_path, "True trajectory (TUM format, e.g. groundtruth.txt)")
      ->required();
  cmd->add_option("--align", o.alignment, "Alignment: none, first, se3 or sim3 (monocular)")
      ->capture_default_str();
  cmd->add_option("--max-dt", o.max_time_difference_s, "Association tolerance, seconds")
      ->capture_default_str();
  cmd->add_option("--segment", o.rpe_segment_m, "RPE segment length along the true path, metres")
      ->capture_default_str();
  cmd->add_option("--json", o.json_path, "Write the figures as JSON to this file");
  cmd->add_option("--plot", o.plot_path, "Write a top-down PNG of both trajectories");
  return cmd;
}

int runEvalTrajectory(const EvalTrajectoryOptions& o) {
  try {
    trajectory::TrajectoryErrorOptions options;
    options.alignment = trajectory::parseAlignment(o.alignment);
    options.max_time_difference_s = o.max_time_difference_s;
    options.rpe_segment_m = o.rpe_segment_m;
    const auto estimate = tum::readTrajectory(o.estimate_path);
    const auto truth = tum::readTrajectory(o.truth_path);
    const trajectory::TrajectoryError e = trajectory::evaluateTrajectory(estimate, truth, options);
    std::printf("%zu of %zu poses matched over %.2f s and %.3f m of true path (alignment %s, "
                "scale %.4f)\n",
                e.matched, e.estimated, e.duration_s, e.path_length_m,
                trajectory::alignmentName(e.alignment), e.scale);
    std::printf("ATE: RMSE %.4f m (%.2f %% of the path), mean %.4f, median %.4f, max %.4f m; "
                "rotation RMSE %.3f deg\n",
                e.ate_rmse_m, e.path_length_m > 0 ? 100.0 * e.ate_rmse_m / e.path_length_m : 0.0,
                e.ate_mean_m, e.ate_median_m, e.ate_max_m, e.rotation_rmse_deg);
    if (e.rpe_pairs > 0) {
      std::printf("RPE over %.2f m segments (%zu): translation %.3f %%, rotation %.4f deg/m\n",
                  e.rpe_segment_m, e.rpe_pairs, e.rpe_trans_percent, e.rpe_rot_deg_per_m);
    } else {
      std::printf("RPE: none (the true path is shorter than one %.2f m segment)\n", e.rpe_segment_m);
    }
    if (!o.json_path.empty()) {
      const std::string json = trajectory::trajectoryErrorJson(e) + "\n";
      writeFileAtomically(o.json_path, std::vector<std::uint8_t>(json.begin(), json.end()));
      std::printf("Wrote %s\n", o.json_path.c_str());
    }
    if (!o.plot_path.empty()) {
      writeTrajectoryPlot(o.plot_path, e);
      std::printf("Wrote %s\n", o.plot_path.c_str());
    }
    return 0;
  } catch (const InputError& e) {
    std::fprintf(stderr, "strata eval-trajectory: input error: %s\n", e.what());
    return 2;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "strata eval-trajectory: error: %s\n", e.what());
    return 1;
  }
}

}  // namespace strata::apps
