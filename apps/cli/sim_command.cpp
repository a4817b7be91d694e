#include "cli/sim_command.h"

#include <CLI/CLI.hpp>
#include <cstdio>
#include <filesystem>

#include "strata/core/progress.h"
#include "strata/sim/sim_setup.h"
#include "strata/core/error.h"
#include "strata/io/odometry_frame_file.h"
#include "strata/io/tum_format.h"
#include "strata/io/tum_writer.h"
#include "strata/sim/sensors/odometry_frame.h"
#include "strata/sim/session/stereo_recording.h"
#include "strata/sim/world/ground_truth.h"

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

}  // namespace

CLI::App* addSimCommand(CLI::App& app, SimOptions& o) {
  CLI::App* sim = app.add_subcommand("sim", "Render a synthetic multi-session world to disk");
  sim->add_option("world", o.world, "World file (YAML); default: the shipped single room");
  sim->add_option("--sessions", o.sessions, "Sessions to render (default: the world's)");
  sim->add_option("--out", o.out_dir, "Output folder")->capture_default_str();
  sim->add_option("--seed", o.seed, "Override the world's seed");
  sim->add_option("--frames", o.max_frames, "Frames per session, spread over the path (0: all)");
  sim->add_option("--rate", o.rate_hz, "Frame rate along the path, Hz")->capture_default_str();
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
      ->capture_default_str();
  sim->add_flag("--stereo", o.stereo,
                "Also write each session as grey stereo + IMU in the EuRoC layout (mav0/)");
  sim->add_flag("--mono", o.mono, "With --stereo: the left camera only");
  sim->add_option("--stereo-duration", o.stereo_duration_s,
                  "With --stereo: record only the first seconds of each path (0: all)");
  sim->add_option("--stereo-width", o.stereo_width_px, "Grey camera width, px")
      ->capture_default_str();
  sim->add_option("--stereo-height", o.stereo_height_px, "Grey camera height, px")
      ->capture_default_str();
  sim->add_option("--exposure-gain-sigma", o.exposure_gain_sigma,
                  "Per-frame exposure gain noise (relative)")
      ->capture_default_str();
  sim->add_option("--exposure-offset-sigma", o.exposure_offset_sigma,
                  "Per-frame exposure offset noise (grey levels)")
      ->capture_default_str();
  return sim;
}

int runSim(const SimOptions& o) {
  try {
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
    const fs::path out(o.out_dir);
    fs::create_directories(out);
    sim::writeGroundTruth(*world, (out / "ground_truth").string());
    const sim::StereoRecordingConfig stereo = stereoConfig(o);
    const std::size_t rgbd_frames = total;
    if (o.stereo) {
      stereo.validate();
      for (const auto& session : sessions) total += sim::stereoFrameCount(*session, stereo);
    }
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
