#include "cli/drift_command.h"

#include <CLI/CLI.hpp>
#include <cmath>
#include <cstdio>

#include "strata/core/error.h"

namespace strata::apps {

CLI::App* addDriftCommand(CLI::App& app, DriftOptions& o) {
  CLI::App* cmd = app.add_subcommand(
      "drift",
      "Write a slice of a TUM RGB-D folder as a session with drifted odometry in a "
      "random frame of its own");
  cmd->add_option("source", o.source_dir, "TUM RGB-D folder (depth.txt, groundtruth.txt)")
      ->required();
  cmd->add_option("--out", o.out_dir, "Output folder (images are listed, not copied)")->required();
  cmd->add_option("--first", o.first_frame, "First depth frame of the slice (index)")
      ->capture_default_str();
  cmd->add_option("--last", o.last_frame,
                  "Last depth frame of the slice, inclusive (default: last)");
  cmd->add_option("--seed", o.config.seed, "Seeds the drift and the frame offset")
      ->capture_default_str();
  cmd->add_option("--translation-sigma", o.config.drift.translation_sigma_m_per_sqrt_m,
                  "Translation drift per axis, m per sqrt(m) travelled")
      ->capture_default_str();
  cmd->add_option("--yaw-sigma", o.config.drift.yaw_sigma_rad_per_sqrt_m,
                  "Yaw drift, rad per sqrt(m) travelled")
      ->capture_default_str();
  cmd->add_option("--offset-translation-m", o.config.frame.horizontal_offset_m,
                  "Frame offset: origin uniform in +-this along x and y, metres")
      ->capture_default_str();
  cmd->add_flag("--no-offset", o.no_offset, "Odometry in the source's world frame (T_W_S = I)");
  return cmd;
}

int runDrift(const DriftOptions& o) {
  try {
    sim::DriftedSessionConfig config = o.config;
    config.first_frame = o.first_frame;
    if (o.last_frame >= 0) config.last_frame = static_cast<std::size_t>(o.last_frame);
    config.offset = !o.no_offset;
    const sim::DriftedSession session = sim::writeDriftedSession(o.source_dir, o.out_dir, config);
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
