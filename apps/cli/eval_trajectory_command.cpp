#include "cli/eval_trajectory_command.h"

#include <CLI/CLI.hpp>
#include <cstdio>

#include "cli/option_checks.h"
#include "cli/run_outputs.h"
#include "cli/trajectory_plot.h"
#include "strata/core/atomic_file.h"
#include "strata/core/error.h"
#include "strata/core/output_paths.h"
#include "strata/trajectory/trajectory_error.h"

namespace strata::apps {
namespace {

/// ATE from fewer poses says nothing (an SE(3) alignment fits any two).
constexpr std::size_t kMinMatchedPoses = 3;

/// The options alone, before any file is read (the parser refuses only NaN and inf).
trajectory::TrajectoryErrorOptions validated(const EvalTrajectoryOptions& o) {
  if (o.estimate_path.empty()) throw InputError("no estimated trajectory given");
  if (o.truth_path.empty()) throw InputError("no true trajectory given");
  trajectory::TrajectoryErrorOptions options;
  options.alignment = trajectory::parseAlignment(o.alignment);
  requireNumber(o.max_time_difference_s, "--max-dt", "seconds", 0.0, true);
  requireNumber(o.rpe_segment_m, "--segment", "metres", 0.0, false);
  options.max_time_difference_s = o.max_time_difference_s;
  options.rpe_segment_m = o.rpe_segment_m;
  return options;
}

void checkPaths(const EvalTrajectoryOptions& o) {
  OutputPaths paths;
  paths.inputFile(o.estimate_path, "the estimated trajectory");
  paths.inputFile(o.truth_path, "the true trajectory");
  paths.outputFile(o.json_path, "--json");
  paths.outputFile(o.plot_path, "--plot");
  paths.check();
}

std::vector<tum::TimedPose> readPoses(const std::string& path, const char* what) {
  std::vector<tum::TimedPose> poses = tum::readTrajectory(path);
  if (poses.empty()) {
    throw InputError(path + ": the " + std::string(what) +
                     " is empty (no 'timestamp tx ty tz qx qy qz qw' line)");
  }
  return poses;
}

/// Refuses an evaluation on fewer than kMinMatchedPoses associated poses, before aligning.
void requireEnoughMatches(const std::vector<tum::TimedPose>& estimate,
                          const std::vector<tum::TimedPose>& truth,
                          const EvalTrajectoryOptions& o) {
  const std::vector<double> truth_s = tum::timestampsOf(truth);
  std::size_t matched = 0;
  for (const tum::TimedPose& p : estimate)
    matched += tum::nearestWithin(truth_s, p.timestamp_s, o.max_time_difference_s) ? 1 : 0;
  if (matched < kMinMatchedPoses) {
    throw InputError(std::to_string(matched) + " of the " + std::to_string(estimate.size()) +
                     " estimated poses have a true pose within --max-dt " +
                     std::to_string(o.max_time_difference_s) + " s: the ATE needs at least " +
                     std::to_string(kMinMatchedPoses) + " associated poses");
  }
}

}  // namespace

CLI::App* addEvalTrajectoryCommand(CLI::App& app, EvalTrajectoryOptions& o) {
  CLI::App* cmd = app.add_subcommand(
      "eval-trajectory", "Trajectory accuracy: ATE after alignment and RPE per metre (TUM files)");
  cmd->add_option("estimate", o.estimate_path, "Estimated trajectory (TUM format)")->required();
  cmd->add_option("truth", o.truth_path, "True trajectory (TUM format, e.g. groundtruth.txt)")
      ->required();
  cmd->add_option("--align", o.alignment, "Alignment: none, first, se3 or sim3 (monocular)")
      ->capture_default_str();
  cmd->add_option("--max-dt", o.max_time_difference_s, "Association tolerance, seconds")
      ->check(finiteNumber())
      ->capture_default_str();
  cmd->add_option("--segment", o.rpe_segment_m, "RPE segment length along the true path, metres")
      ->check(finiteNumber())
      ->capture_default_str();
  cmd->add_option("--json", o.json_path, "Write the figures as JSON to this file");
  cmd->add_option("--plot", o.plot_path, "Write a top-down PNG of both trajectories");
  return cmd;
}

int runEvalTrajectory(const EvalTrajectoryOptions& o) {
  try {
    const trajectory::TrajectoryErrorOptions options = validated(o);
    checkPaths(o);
    const auto estimate = readPoses(o.estimate_path, "estimated trajectory");
    const auto truth = readPoses(o.truth_path, "true trajectory");
    requireEnoughMatches(estimate, truth, o);
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
    OutputCleanup cleanup;  // a plot that fails takes the new JSON with it
    cleanup.file(o.json_path);
    cleanup.file(o.plot_path);
    if (!o.json_path.empty()) {
      const std::string json = trajectory::trajectoryErrorJson(e) + "\n";
      writeFileAtomically(o.json_path, std::vector<std::uint8_t>(json.begin(), json.end()));
      std::printf("Wrote %s\n", o.json_path.c_str());
    }
    if (!o.plot_path.empty()) {
      writeTrajectoryPlot(o.plot_path, e);
      std::printf("Wrote %s\n", o.plot_path.c_str());
    }
    cleanup.keep();
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
