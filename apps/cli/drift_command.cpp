#include "cli/drift_command.h"

#include <CLI/CLI.hpp>
#include <cmath>
#include <cstdio>
#include <filesystem>

#include "cli/option_checks.h"
#include "cli/run_outputs.h"
#include "strata/core/error.h"
#include "strata/core/output_paths.h"

namespace strata::apps {
namespace {

namespace fs = std::filesystem;

/// The options alone, before the source is read (the parser refuses only NaN, inf and negative
/// indices; tests call runDrift without it); then the config's own checks (first <= last).
sim::DriftedSessionConfig validated(const DriftOptions& o) {
  if (o.source_dir.empty()) throw InputError("no source folder given");
  if (o.out_dir.empty()) throw InputError("--out must name a folder");
  if (o.last_frame < -1) {
    throw InputError("--last must be >= 0 (a frame index; got " + std::to_string(o.last_frame) +
                     ")");
  }
  requireNumber(o.config.drift.translation_sigma_m_per_sqrt_m, "--translation-sigma",
                "m per sqrt(m)", 0.0, true);
  requireNumber(o.config.drift.yaw_sigma_rad_per_sqrt_m, "--yaw-sigma", "rad per sqrt(m)", 0.0,
                true);
  requireNumber(o.config.frame.horizontal_offset_m, "--offset-translation-m", "metres", 0.0,
                true);
  sim::DriftedSessionConfig config = o.config;
  config.first_frame = o.first_frame;
  if (o.last_frame >= 0) config.last_frame = static_cast<std::size_t>(o.last_frame);
  config.offset = !o.no_offset;
  config.validate();
  return config;
}

/// A frame index: refuses "-5" before the unsigned option wraps it to 2^64 - 5.
CLI::Validator frameIndex() {
  return CLI::Validator(
      [](std::string& input) -> std::string {
        const std::size_t first = input.find_first_not_of(" \t");
        if (first != std::string::npos && input[first] == '-') {
          return "Value " + input + " is not a frame index (0 or more)";
        }
        return std::string();
      },
      "INDEX >= 0", "FRAME_INDEX");
}

/// The files writeDriftedSession writes into --out.
const std::vector<std::string> kOutputFiles = {"depth.txt",    "rgb.txt",
                                               "groundtruth.txt", "odometry.txt",
                                               "odometry_frame.txt", "camera.yaml"};

}  // namespace

CLI::App* addDriftCommand(CLI::App& app, DriftOptions& o) {
  CLI::App* cmd = app.add_subcommand(
      "drift",
      "Write a slice of a TUM RGB-D folder as a session with drifted odometry in a "
      "random frame of its own");
  cmd->add_option("source", o.source_dir, "TUM RGB-D folder (depth.txt, groundtruth.txt)")
      ->required();
  cmd->add_option("--out", o.out_dir, "Output folder (images are listed, not copied)")->required();
  cmd->add_option("--first", o.first_frame, "First depth frame of the slice (index)")
      ->check(frameIndex())
      ->capture_default_str();
  cmd->add_option("--last", o.last_frame,
                  "Last depth frame of the slice, inclusive (default: last)")
      ->check(frameIndex());
  cmd->add_option("--seed", o.config.seed, "Seeds the drift and the frame offset")
      ->capture_default_str();
  cmd->add_option("--translation-sigma", o.config.drift.translation_sigma_m_per_sqrt_m,
                  "Translation drift per axis, m per sqrt(m) travelled")
      ->check(finiteNumber())
      ->capture_default_str();
  cmd->add_option("--yaw-sigma", o.config.drift.yaw_sigma_rad_per_sqrt_m,
                  "Yaw drift, rad per sqrt(m) travelled")
      ->check(finiteNumber())
      ->capture_default_str();
  cmd->add_option("--offset-translation-m", o.config.frame.horizontal_offset_m,
                  "Frame offset: origin uniform in +-this along x and y, metres")
      ->check(finiteNumber())
      ->capture_default_str();
  cmd->add_flag("--no-offset", o.no_offset, "Odometry in the source's world frame (T_W_S = I)");
  return cmd;
}

int runDrift(const DriftOptions& o) {
  try {
    const sim::DriftedSessionConfig config = validated(o);
    std::error_code error;
    if (!fs::is_directory(o.source_dir, error)) {
      throw InputError(o.source_dir +
                       (fs::exists(o.source_dir, error) ? ": not a folder" : ": no such folder"));
    }
    OutputPaths paths;
    paths.inputFolder(o.source_dir, "the source folder");
    paths.outputFolder(o.out_dir, "--out");
    paths.check();
    OutputCleanup cleanup;  // a failed run leaves no new folder or file behind
    cleanup.folder(o.out_dir, kOutputFiles);
    const sim::DriftedSession session = sim::writeDriftedSession(o.source_dir, o.out_dir, config);
    cleanup.keep();
    const Eigen::Vector3d t_m = session.T_W_S.translation();
    const double yaw_deg =
        std::atan2(session.T_W_S.linear()(1, 0), session.T_W_S.linear()(0, 0)) * 180.0 / M_PI;
    std::printf(
        "Wrote %zu frames of %s to %s (%zu without a pose left out); odometry frame T_W_S: yaw "
        "%.2f deg, t = (%.3f, %.3f, %.3f) m (odometry_frame.txt).\n",
        session.frames, o.source_dir.c_str(), o.out_dir.c_str(), session.frames_dropped, yaw_deg,
        t_m.x(), t_m.y(), t_m.z());
    return 0;
  } catch (const InputError& e) {
    std::fprintf(stderr, "strata drift: input error: %s\n", e.what());
    return 2;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "strata drift: error: %s\n", e.what());
    return 1;
  }
}

}  // namespace strata::apps
