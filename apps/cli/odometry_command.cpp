#include "cli/odometry_command.h"

#include <time.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>

#include "cli/odometry_summary.h"
#include "cli/run_outputs.h"
#include "strata/core/progress.h"
#include "cli/trajectory_plot.h"
#include "strata/core/atomic_file.h"
#include "strata/core/error.h"
#include "strata/core/output_paths.h"
#include "strata/io/tum_format.h"
#include "strata/odometry/pipeline/vio_replay.h"
#include "strata/odometry/solver_log.h"
#include "strata/io/tum_writer.h"

namespace strata::apps {
namespace {

namespace fs = std::filesystem;

// CPU time of the whole process: what the replay costs whatever else loads the machine.
double processCpuSeconds() {
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

odometry::VioPipelineConfig pipelineConfig(const OdometryOptions& o,
                                           const euroc::EurocDataset& dataset) {
  odometry::VioPipelineConfig config;
  config.mono = o.mono;
  config.backend.window_size = o.window;
  if (o.max_features > 0) config.frontend.detector.target_features = o.max_features;
  if (o.anchor_to_truth) {
    if (dataset.groundTruth().empty()) {
      throw InputError(o.session_dir +
                       ": --anchor-to-truth needs ground truth, the session has none");
    }
    config.anchor_W_B = odometry::truthAnchor(dataset.groundTruth());
  }
  return config;
}

void writeTrajectory(const std::string& path, const std::vector<odometry::PipelineFrame>& tracked) {
  std::vector<tum::TimedPose> poses;
  for (const auto& f : tracked)
    poses.push_back({1e-9 * static_cast<double>(f.timestamp_ns), f.T_W_C});
  writeTumTrajectory(path, poses,
                     {"timestamp tx ty tz qx qy qz qw (left camera to world, strata odometry)"}, 9);
}

std::string frameCsvRow(const odometry::PipelineFrame& f) {
  std::string reason = f.reason;
  for (char& c : reason) {
    if (c == ',' || c == '\n') c = ';';
  }
  char row[256];
  std::snprintf(row, sizeof(row), "%.9f,%s,%d,%d,%d,%d,%d,%.4f,%.2f,%.2f,",
                1e-9 * static_cast<double>(f.timestamp_ns), odometry::toString(f.status), f.segment,
                f.features, f.stereo_matched, f.frontend_lost ? 1 : 0, f.landmarks, f.v_W_B.norm(),
                f.frontend_ms, f.backend_ms);
  return row + reason + "\n";
}

std::string defaultSummaryPath(const std::string& out_path) {
  std::filesystem::path p(out_path);
  p.replace_extension(".json");
  return p.string();
}

/// The options alone, before any file is read (here, not in the parser: tests call runOdometry
/// without it, and bad input exits 2).
void validate(const OdometryOptions& o) {
  if (o.mode != "vio") {
    throw InputError("--mode " + o.mode +
                     " is not known (vio; RGB-D tracking is `strata fuse --track`)");
  }
  if (o.session_dir.empty()) throw InputError("no session folder given");
  if (o.window < 2) {
    throw InputError("--window must be at least 2 (got " + std::to_string(o.window) + ")");
  }
  if (o.max_features < 0) {
    throw InputError("--features must be >= 0 (0: the front end's default; got " +
                     std::to_string(o.max_features) + ")");
  }
  if (o.frames < 0) {
    throw InputError("--frames must be >= 0 (0: all; got " + std::to_string(o.frames) + ")");
  }
  if (o.out_path.empty()) throw InputError("--out must name a file");
}

/// The session's mav0 folder as EurocDataset::open finds it, and the folder holding it.
std::pair<fs::path, fs::path> sessionFolders(const std::string& session_dir) {
  const fs::path root(session_dir);
  std::error_code error;
  if (!fs::is_directory(root / "mav0", error) && fs::is_directory(root / "cam0", error)) {
    return {root, fs::absolute(root, error).parent_path()};  // opened at mav0/ itself
  }
  return {root / "mav0", root};
}

/// Every output against the session's files and each other, before anything is read. The inputs
/// are mav0/ (images, IMU, calibration, truth) and groundtruth_body.txt, not the whole session
/// folder: outputs beside them (e.g. SESSION/vio.txt, rewritten by a second run) are fine.
void checkPaths(const OdometryOptions& o, const std::string& summary_path) {
  const auto [mav0, session] = sessionFolders(o.session_dir);
  OutputPaths paths;
  paths.inputFolder(mav0.string(), "the session's mav0 folder");
  paths.inputFile((session / "groundtruth_body.txt").string(),
                  "the session's groundtruth_body.txt");
  paths.outputFile(o.out_path, "--out");
  paths.outputFile(summary_path,
                   o.summary_path.empty() ? "--summary (default: --out with .json)" : "--summary");
  paths.outputFile(o.plot_path, "--plot");
  paths.outputFile(o.frames_csv_path, "--frames-csv");
  paths.check();
}

/// Stereo unless --mono: a session without a right camera is refused, not run as mono.
void requireRightCamera(const OdometryOptions& o) {
  if (o.mono) return;
  const fs::path mav0 = sessionFolders(o.session_dir).first;
  std::error_code error;
  if (fs::is_directory(mav0, error) && !fs::exists(mav0 / "cam1", error)) {
    throw InputError(o.session_dir + ": the session has no right camera (" +
                     (mav0 / "cam1").string() +
                     " is missing): stereo VIO needs it; give --mono to run on cam0 alone");
  }
}

/// The first tracked frame whose pose is not finite (the estimate diverged), or null.
const odometry::PipelineFrame* firstNonFinite(const std::vector<odometry::PipelineFrame>& frames) {
  for (const auto& f : frames) {
    if (!f.T_W_C.matrix().allFinite() || !f.v_W_B.allFinite()) return &f;
  }
  return nullptr;
}

// Replays the session through the pipeline, reporting failures as they happen.
OdometryRun replay(const OdometryOptions& o, const euroc::EurocDataset& dataset) {
  OdometryRun run;
  run.session_dir = o.session_dir;
  run.reader = dataset.stats();
  run.frames_in_dataset = dataset.frames().size();
  odometry::ReplayInput input;
  input.imu = &dataset.imu();
  for (const euroc::StereoFrame& f : dataset.frames())
    input.frame_timestamps_ns.push_back(f.timestamp_ns);
  input.load = [&](std::size_t k) { return dataset.loadImages(k); };
  input.max_frames = o.frames > 0 ? static_cast<std::size_t>(o.frames) : 0;
  const std::size_t frames = input.max_frames > 0
                                 ? std::min(input.max_frames, run.frames_in_dataset)
                                 : run.frames_in_dataset;
  ProgressBar progress("odometry", frames, !o.quiet);
  std::string frames_csv =
      "timestamp_s,status,segment,features,stereo_matched,frontend_lost,landmarks,speed_mps,"
      "frontend_ms,backend_ms,reason\n";
  input.on_processed = [&](const odometry::PipelineFrame& f) {
    if (!o.frames_csv_path.empty()) frames_csv += frameCsvRow(f);
    if (f.status == odometry::VioStatus::kFailed && !o.quiet) {
      std::fprintf(stderr, "\nstrata odometry: tracking lost at %.3f s: %s (re-initialising)\n",
                   1e-9 * static_cast<double>(f.timestamp_ns), f.reason.c_str());
    }
  };
  input.on_pushed = [&](std::size_t pushed, const odometry::PipelineStats& s) {
    char detail[96];
    std::snprintf(
        detail, sizeof(detail), "%zu tracked, %zu failures, %.1f ms/frame", s.frames_tracking,
        s.failures,
        (s.frontend_ms_total + s.backend_ms_total) / std::max<std::size_t>(1, s.frames_processed));
    progress.update(pushed, detail);
  };
  odometry::VioPipeline pipeline(dataset.calibration(), pipelineConfig(o, dataset));
  const double cpu_start = processCpuSeconds();
  odometry::ReplayResult result = odometry::replayVio(pipeline, input);
  run.cpu_s = processCpuSeconds() - cpu_start;
  progress.finish();
  if (!o.frames_csv_path.empty()) {
    writeFileAtomically(o.frames_csv_path,
                        std::vector<std::uint8_t>(frames_csv.begin(), frames_csv.end()));
  }
  run.stereo = result.stereo;
  run.wall_s = result.wall_s;
  run.image_load_s = result.image_load_s;
  run.stats = std::move(result.stats);
  run.tracked = std::move(result.tracked);
  return run;
}

constexpr double kMinPathForRates_m = 1.0;

void printAccuracy(const OdometryAccuracy& a, bool stereo) {
  const auto& headline = stereo ? a.se3 : a.sim3;
  if (headline) {
    const auto& e = *headline;
    // A share of the path or a per-metre drift of a path shorter than a metre says nothing.
    if (e.path_length_m >= kMinPathForRates_m && std::isfinite(e.rpe_trans_percent)) {
      std::printf(
          "ATE (%s): RMSE %.4f m = %.2f %% of %.2f m of path, max %.4f m; RPE %.2f %%, "
          "%.3f deg/m\n",
          trajectory::alignmentName(e.alignment), e.ate_rmse_m,
          100.0 * e.ate_rmse_m / e.path_length_m, e.path_length_m, e.ate_max_m,
          e.rpe_trans_percent, e.rpe_rot_deg_per_m);
    } else {
      std::printf("ATE (%s): RMSE %.4f m, max %.4f m over %.2f m of tracked path (shorter than "
                  "%.0f m: no share of the path nor RPE)\n",
                  trajectory::alignmentName(e.alignment), e.ate_rmse_m, e.ate_max_m,
                  e.path_length_m, kMinPathForRates_m);
    }
    if (!stereo) std::printf("Sim(3) scale %.4f (1 = the IMU gave the true scale)\n", e.scale);
  }
  if (a.first) std::printf("Drift from the first pose: max %.4f m\n", a.first->ate_max_m);
  std::printf("Gravity direction error: %.3f deg at initialisation, max %.3f deg\n",
              a.gravity_error_first_deg, a.gravity_error_max_deg);
}

}  // namespace

CLI::App* addOdometryCommand(CLI::App& app, OdometryOptions& o) {
  CLI::App* cmd = app.add_subcommand(
      "odometry", "Visual-inertial odometry over an EuRoC/ASL session (grey stereo or mono + IMU)");
  cmd->add_option("session", o.session_dir, "Session folder holding mav0/ (or mav0/ itself)")
      ->required();
  cmd->add_option("--mode", o.mode, "Odometry mode: vio")->capture_default_str();
  cmd->add_flag("--mono", o.mono, "Left camera only (scale from the IMU)");
  cmd->add_option("--out", o.out_path, "Trajectory of the left camera (TUM format)")
      ->capture_default_str();
  cmd->add_option("--summary", o.summary_path, "JSON summary (default: --out with .json)");
  cmd->add_option("--plot", o.plot_path, "Top-down PNG of the trajectory against the truth");
  cmd->add_flag("--anchor-to-truth", o.anchor_to_truth,
                "Start the world frame at the true pose (yaw, position) when tracking starts");
  // NOTE: the counts are checked by runOdometry (exit 2 naming the option and its range).
  cmd->add_option("--window", o.window, "Keyframes in the sliding window (at least 2)")
      ->capture_default_str();
  cmd->add_option("--features", o.max_features, "Tracks the front end keeps (0: its default)");
  cmd->add_option("--frames", o.frames, "Process only the first N frames (0: all)");
  cmd->add_option("--frames-csv", o.frames_csv_path,
                  "Per-frame CSV: status, features, stereo matches, landmarks, speed, ms, reason");
  cmd->add_flag("--quiet", o.quiet, "No progress bar");
  cmd->add_flag("--solver-log", o.solver_log,
                "Show the solver's own log (Ceres) on stderr; without it, only a count");
  return cmd;
}

int runOdometry(const OdometryOptions& o) {
  try {
    validate(o);
    const std::string summary_path =
        o.summary_path.empty() ? defaultSummaryPath(o.out_path) : o.summary_path;
    checkPaths(o, summary_path);
    requireRightCamera(o);
    const euroc::EurocDataset dataset =
        euroc::EurocDataset::open(o.session_dir, euroc::ReaderOptions{1'000'000, !o.mono});
    if (!o.mono && !dataset.stereo()) {
      throw InputError(o.session_dir + ": the session has no right camera: stereo VIO needs it; "
                       "give --mono to run on cam0 alone");
    }
    OutputCleanup cleanup;  // a write that fails takes this run's other new outputs with it
    for (const std::string& path : {o.out_path, summary_path, o.plot_path, o.frames_csv_path})
      cleanup.file(path);
    const odometry::SolverLog& solver = odometry::SolverLog::install("strata", o.solver_log);
    OdometryRun run = replay(o, dataset);
    if (!solver.summary().empty()) {
      std::fprintf(stderr, "strata odometry: %s\n", solver.summary().c_str());
    }
    if (run.stats.imu_out_of_range_skipped > 0) {
      std::fprintf(stderr, "strata odometry: %s\n",
                   odometry::imuOutOfRangeWarning(run.stats.imu_out_of_range_skipped).c_str());
    }
    const auto write_summary = [&] {
      const std::string json = odometrySummaryJson(run);
      writeFileAtomically(summary_path, std::vector<std::uint8_t>(json.begin(), json.end()));
    };
    // A failed run writes no trajectory (nor plot); its summary records the failures.
    if (run.tracked.empty()) {
      write_summary();
      std::fprintf(stderr,
                   "strata odometry: no frame was tracked (%s); no trajectory written, the "
                   "failures are in %s\n",
                   run.stats.failure_log.empty() ? "never initialised"
                                                 : run.stats.failure_log.back().second.c_str(),
                   summary_path.c_str());
      cleanup.keep();  // the summary and the frames CSV say why
      return 3;
    }
    if (const odometry::PipelineFrame* bad = firstNonFinite(run.tracked)) {
      write_summary();
      std::fprintf(stderr,
                   "strata odometry: the estimate diverged: the pose at %.3f s is not finite; "
                   "no trajectory written, the run's counts are in %s\n",
                   1e-9 * static_cast<double>(bad->timestamp_ns), summary_path.c_str());
      cleanup.keep();  // the summary and the frames CSV say why
      return 3;
    }
    run.accuracy = evaluateOdometry(dataset, run.tracked);
    writeTrajectory(o.out_path, run.tracked);
    write_summary();
    const auto& s = run.stats;
    std::printf(
        "%s VIO: %zu of %zu frames tracked, %zu failures, %.1f frames/s (front end %.1f + "
        "back end %.1f ms/frame); %.1f frames per CPU second, PNG decoding included\n",
        run.stereo ? "Stereo" : "Mono", s.frames_tracking, s.frames_processed, s.failures,
        s.frames_processed / std::max(1e-9, 1e-3 * (s.frontend_ms_total + s.backend_ms_total)),
        s.frontend_ms_total / std::max<std::size_t>(1, s.frames_processed),
        s.backend_ms_total / std::max<std::size_t>(1, s.frames_processed),
        s.frames_processed / std::max(1e-9, run.cpu_s));
    if (s.frames_without_imu_skipped > 0) {
      std::printf("%zu frames skipped: their IMU never came (see the summary's skipped counts)\n",
                  s.frames_without_imu_skipped);
    }
    if (run.accuracy) printAccuracy(*run.accuracy, run.stereo);
    std::printf("Wrote %s and %s\n", o.out_path.c_str(), summary_path.c_str());
    if (!o.plot_path.empty() && run.accuracy) {
      const auto& e = run.stereo ? run.accuracy->se3 : run.accuracy->sim3;
      if (e) {
        writeTrajectoryPlot(o.plot_path, *e);
        std::printf("Wrote %s\n", o.plot_path.c_str());
      }
    }
    cleanup.keep();
    return 0;
  } catch (const InputError& e) {
    std::fprintf(stderr, "strata odometry: input error: %s\n", e.what());
    return 2;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "strata odometry: error: %s\n", e.what());
    return 1;
  }
}

}  // namespace strata::apps
