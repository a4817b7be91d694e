#include "cli/sim_command.h"

#include <CLI/CLI.hpp>
#include <cmath>
#include <cstdio>
#include <filesystem>

#include "cli/option_checks.h"
#include "cli/run_outputs.h"
#include "strata/core/progress.h"
#include "strata/sim/sim_setup.h"
#include "strata/core/error.h"
#include "strata/core/image_limits.h"
#include "strata/core/output_paths.h"
#include "strata/io/odometry_frame_file.h"
#include "strata/io/tum_format.h"
#include "strata/io/tum_writer.h"
#include "strata/sim/sensors/odometry_frame.h"
#include "strata/sim/session/stereo_recording.h"
#include "strata/sim/world/ground_truth.h"
#include "strata/sim/world/world_paths.h"

namespace strata::apps {
namespace {

namespace fs = std::filesystem;

/// The poses handed to a mapper (drifted odometry), in the groundtruth.txt format: in the world
/// frame, or with `own_frame` in a random frame of the session's own (T_S_C = T_S_W * drifted
/// T_W_C), whose T_W_S goes to odometry_frame.txt.
void writeOdometry(const fs::path& dir, const sim::SimSessionDataset& session, bool own_frame) {
  Eigen::Isometry3d T_W_S = Eigen::Isometry3d::Identity();
  if (own_frame) T_W_S = sim::randomOdometryFrame({}, session.seed());
  const std::vector<Eigen::Isometry3d> T_S_C =
      sim::posesInFrame(T_W_S.inverse(), session.givenPoses());
  std::vector<tum::TimedPose> poses;
  for (std::size_t i = 0; i < session.size(); ++i)
    poses.push_back({session.timestamp(i), T_S_C[i]});
  const char* frame = own_frame ? "session frame S, see odometry_frame.txt" : "world";
  writeTumTrajectory((dir / "odometry.txt").string(), poses,
                     {"odometry given to the mapper (drifted); groundtruth.txt holds the truth",
                      std::string("timestamp tx ty tz qx qy qz qw (camera-to-") + frame + ")"});
  if (own_frame) writeOdometryFrame((dir / "odometry_frame.txt").string(), T_W_S);
}

std::size_t writeSession(const sim::SimSessionDataset& session, const fs::path& dir,
                         const SimOptions& o, ProgressBar& progress, std::size_t& done) {
  TumWriter writer(dir.string(), session.intrinsics());
  for (std::size_t i = 0; i < session.size(); ++i) {
    RgbdFrame frame = session.load(i);
    frame.T_W_C = session.truePoses()[i];  // groundtruth.txt holds the truth
    writer.add(frame);
    progress.update(++done);
  }
  writer.finish();
  if (o.drift || o.own_frames) writeOdometry(dir, session, o.own_frames);
  fs::create_directories(dir / "imu0");
  sim::writeImuCsv((dir / "imu0" / "data.csv").string(), session.imu());
  return session.size();
}

sim::StereoRecordingConfig stereoConfig(const SimOptions& o) {
  sim::StereoRecordingConfig config =
      sim::stereoRecordingConfig(o.stereo_width_px, o.stereo_height_px, !o.no_noise);
  config.stereo = !o.mono;
  config.duration_s = o.stereo_duration_s;
  if (!o.no_noise) {
    config.exposure_gain_sigma = o.exposure_gain_sigma;
    config.exposure_offset_sigma = o.exposure_offset_sigma;
  }
  return config;
}

/// Most sessions a world may have (as in a world file's `sessions`).
constexpr int kMaxSessions = 1000;

/// The options alone, before the world file is read or anything is written (the parser refuses
/// only NaN, inf and out-of-range sizes; tests call runSim without it).
void validate(const SimOptions& o) {
  if (o.out_dir.empty()) throw InputError("--out must name a folder");
  if (o.sessions < 0 || o.sessions > kMaxSessions) {
    throw InputError("--sessions must be in 0.." + std::to_string(kMaxSessions) +
                     " (0: the world file's count; got " + std::to_string(o.sessions) + ")");
  }
  if (o.max_frames < 0 || o.max_frames == 1) {
    throw InputError("--frames must be 0 (every frame) or at least 2 (got " +
                     std::to_string(o.max_frames) + ")");
  }
  requireNumber(o.rate_hz, "--rate", "Hz", 0.0, false);
  requireNumber(o.rest_s, "--rest", "seconds", 0.0, true);
  requireNumber(o.stereo_duration_s, "--stereo-duration", "seconds; 0: all", 0.0, true);
  for (const auto& [value, option] : {std::pair{o.stereo_width_px, "--stereo-width"},
                                      std::pair{o.stereo_height_px, "--stereo-height"}}) {
    if (value < 8 || value > kMaxImageSidePx) {
      throw InputError(std::string(option) + " must be in 8.." + std::to_string(kMaxImageSidePx) +
                       " pixels (got " + std::to_string(value) + ")");
    }
  }
  if (!std::isfinite(o.exposure_gain_sigma) || o.exposure_gain_sigma < 0.0 ||
      o.exposure_gain_sigma >= 0.5) {
    throw InputError("--exposure-gain-sigma must be in [0, 0.5) (got " +
                     std::to_string(o.exposure_gain_sigma) + ")");
  }
  requireNumber(o.exposure_offset_sigma, "--exposure-offset-sigma", "grey levels", 0.0, true);
  if (o.mono && !o.stereo) throw InputError("--mono needs --stereo (it keeps cam0 of the stereo)");
  if (o.stereo) stereoConfig(o).validate();
}

/// A seed: refuses "-5" before the unsigned option wraps it to 2^64 - 5.
CLI::Validator unsignedNumber() {
  return CLI::Validator(
      [](std::string& input) -> std::string {
        const std::size_t first = input.find_first_not_of(" \t");
        if (first != std::string::npos && input[first] == '-') {
          return "Value " + input + " is negative (0 or more)";
        }
        return std::string();
      },
      "UINT", "UNSIGNED");
}

}  // namespace

CLI::App* addSimCommand(CLI::App& app, SimOptions& o) {
  CLI::App* sim = app.add_subcommand("sim", "Render a synthetic multi-session world to disk");
  sim->add_option("world", o.world, "World file (YAML); default: the shipped single room");
  sim->add_option("--sessions", o.sessions, "Sessions to render (default: the world's)")
      ->check(CLI::Range(0, kMaxSessions));
  sim->add_option("--out", o.out_dir, "Output folder")->capture_default_str();
  sim->add_option("--seed", o.seed, "Override the world's seed")->check(unsignedNumber());
  // NOTE: the counts and ranges are checked by runSim (exit 2 naming the option and its range).
  sim->add_option("--frames", o.max_frames,
                  "Frames per session, spread over the path (0: all; else at least 2)");
  sim->add_option("--rate", o.rate_hz, "Frame rate along the path, Hz")
      ->check(finiteNumber())
      ->capture_default_str();
  sim->add_flag("--no-noise", o.no_noise, "Exact depth (16-bit quantisation only)");
  sim->add_flag("--drift", o.drift, "Also write drifted odometry (odometry.txt)");
  sim->add_flag("--color-texture", o.color_texture,
                "The RGB camera sees the world-anchored texture the grey camera sees (corners for "
                "feature detectors, as real surfaces have; default: flat-shaded colour)");
  sim->add_flag("--own-frames", o.own_frames,
                "Odometry of each session in a random gravity-aligned frame of its own, true "
                "offset in odometry_frame.txt (implies --drift)");
  sim->add_flag("--quiet", o.quiet, "No progress bar");
  sim->add_option("--rest", o.rest_s,
                  "Seconds the camera rests before each path starts (no sway; VIO standstill)")
      ->check(finiteNumber())
      ->capture_default_str();
  sim->add_flag("--stereo", o.stereo,
                "Also write each session as grey stereo + IMU in the EuRoC layout (mav0/)");
  sim->add_flag("--mono", o.mono, "With --stereo: the left camera only");
  sim->add_option("--stereo-duration", o.stereo_duration_s,
                  "With --stereo: record only the first seconds of each path (0: all)")
      ->check(finiteNumber());
  sim->add_option("--stereo-width", o.stereo_width_px, "Grey camera width, px")
      ->check(CLI::Range(8, kMaxImageSidePx))
      ->capture_default_str();
  sim->add_option("--stereo-height", o.stereo_height_px, "Grey camera height, px")
      ->check(CLI::Range(8, kMaxImageSidePx))
      ->capture_default_str();
  sim->add_option("--exposure-gain-sigma", o.exposure_gain_sigma,
                  "Per-frame exposure gain noise (relative, below 0.5)")
      ->check(finiteNumber())
      ->capture_default_str();
  sim->add_option("--exposure-offset-sigma", o.exposure_offset_sigma,
                  "Per-frame exposure offset noise (grey levels)")
      ->check(finiteNumber())
      ->capture_default_str();
  return sim;
}

int runSim(const SimOptions& o) {
  try {
    validate(o);
    OutputPaths paths;
    paths.inputFile(o.world.empty() ? sim::defaultWorldPath() : o.world, "the world file");
    paths.outputFolder(o.out_dir, "--out");
    paths.check();
    const auto world = sim::loadWorld(o.world, o.seed, o.sessions);
    sim::SimSessionConfig config =
        sim::sessionConfig(o.rate_hz, o.max_frames, !o.no_noise, o.drift || o.own_frames);
    config.trajectory.rest_at_start_s = o.rest_s;
    if (o.color_texture) config.camera.color_texture = sim::WorldTextureConfig{};
    std::vector<std::unique_ptr<sim::SimSessionDataset>> sessions;
    std::size_t total = 0;
    for (int s = 0; s < world->sessionCount(); ++s) {
      sessions.push_back(std::make_unique<sim::SimSessionDataset>(world, s, config));
      total += sessions.back()->size();
    }
    const sim::StereoRecordingConfig stereo = stereoConfig(o);
    const std::size_t rgbd_frames = total;
    if (o.stereo) {
      for (const auto& session : sessions) total += sim::stereoFrameCount(*session, stereo);
    }
    const fs::path out(o.out_dir);
    OutputCleanup cleanup;  // a failed run leaves no new folder behind
    cleanup.folder(o.out_dir, {"ground_truth", "session_*"});
    fs::create_directories(out);
    sim::writeGroundTruth(*world, (out / "ground_truth").string());
    ProgressBar progress("rendering", total, !o.quiet);
    std::size_t done = 0;
    for (const auto& session : sessions) {
      char name[32];
      std::snprintf(name, sizeof(name), "session_%d", session->session());
      writeSession(*session, out / name, o, progress, done);
      if (o.stereo) {
        sim::writeStereoRecording(*session, stereo, (out / name).string(),
                                  [&] { progress.update(++done); });
      }
    }
    progress.finish();
    cleanup.keep();
    std::printf(
        "Rendered %d sessions of world '%s' (seed %llu), %zu frames at %dx%d, into %s "
        "(TUM RGB-D per session, IMU in EuRoC layout, ground truth in ground_truth/%s).\n",
        world->sessionCount(), world->name().c_str(),
        static_cast<unsigned long long>(world->seed()), rgbd_frames,
        config.camera.intrinsics.width_px, config.camera.intrinsics.height_px, o.out_dir.c_str(),
        o.stereo ? (o.mono ? "; grey mono + IMU in mav0/" : "; grey stereo + IMU in mav0/") : "");
    return 0;
  } catch (const InputError& e) {
    std::fprintf(stderr, "strata sim: input error: %s\n", e.what());
    return 2;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "strata sim: error: %s\n", e.what());
    return 1;
  }
}

}  // namespace strata::apps
