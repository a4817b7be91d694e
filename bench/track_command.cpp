#include "track_command.h"

#include <CLI/CLI.hpp>
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>

#include "strata/core/error.h"
#include "strata/core/statistics.h"
#include "json.h"
#include "machine_info.h"
#include "strata/mapper/mapper.h"
#include "preload.h"
#include "track_peer.h"
#include "strata/track/gauss_newton.h"
#include "strata/trajectory/trajectory_error.h"
#include "bench_timing.h"

namespace strata::bench {
namespace {

/// Self-check: Strata's ATE on the redkitchen frames stays under this (the acceptance bound).
constexpr double kSelfCheckAte_m = 0.03;

trajectory::TrajectoryError ate(const PreloadedFrames& data,
                          const std::vector<Eigen::Isometry3d>& estimate,
                          const std::vector<bool>& present,
                          trajectory::Alignment alignment = trajectory::Alignment::kSE3) {
  std::vector<trajectory::StampedPose> est, truth;
  for (std::size_t i = 0; i < data.frames.size(); ++i) {
    truth.push_back({data.frames[i].timestamp_s, data.frames[i].T_W_C});
    if (present[i]) est.push_back({data.frames[i].timestamp_s, estimate[i]});
  }
  return trajectory::evaluateTrajectory(est, truth, alignment);
}

/// ATE after SE(3) alignment, and the drift from the first pose (both start at the dataset's
/// first pose). NOTE: on a short, nearly straight path the SE(3) fit of positions leaves the
/// rotation about the path free, so rotation errors are given from the first-pose alignment.
Json ateJson(const PreloadedFrames& data, const std::vector<Eigen::Isometry3d>& estimate,
             const std::vector<bool>& present) {
  const trajectory::TrajectoryError se3 = ate(data, estimate, present);
  const trajectory::TrajectoryError first = ate(data, estimate, present, trajectory::Alignment::kFirstPose);
  return Json::object()
      .set("matched", se3.matched)
      .set("path_length_m", se3.path_length_m)
      .set("ate_rmse_m", se3.ate_rmse_m)
      .set("ate_max_m", se3.ate_max_m)
      .set("first_pose_position_rmse_m", first.ate_rmse_m)
      .set("first_pose_position_max_m", first.ate_max_m)
      .set("first_pose_rotation_rmse_deg", first.rotation_rmse_deg);
}

struct StrataRun {
  std::string device;
  std::vector<Eigen::Isometry3d> T_W_C;
  std::vector<bool> fused;
  std::vector<double> track_ms, device_ms, fusion_ms;
  std::size_t lost = 0;
  double iterations = 0.0;
  // The tracked frames' figures nearest to the failure rules (docs/track.md).
  double lowest_eigenvalue = 1e300, lowest_inlier_fraction = 1.0, highest_rms_m = 0.0;
  // The stated uncertainty per tracked frame (TrackResult), index = frame.
  std::vector<double> translation_sigma_m, rotation_sigma_deg;
};

/// The stated uncertainty against the error the frame added: the error of the motion from the
/// previous fused frame to this one against the dataset's (the model the frame was tracked
/// against carries the earlier frames' errors, which the frame did not make).
Json uncertaintyJson(const PreloadedFrames& data, const StrataRun& run) {
  std::vector<double> ratio_t, sigma_t, step_t;
  std::size_t within_3sigma = 0, tracked = 0;
  Json frames = Json::array();
  std::size_t previous = 0;
  for (std::size_t i = 1; i < data.frames.size(); ++i) {
    if (!run.fused[i]) continue;
    const Eigen::Isometry3d est = run.T_W_C[previous].inverse() * run.T_W_C[i];
    const Eigen::Isometry3d truth = data.frames[previous].T_W_C.inverse() * data.frames[i].T_W_C;
    const Eigen::Isometry3d error = truth.inverse() * est;
    const double e_t = error.translation().norm();
    const double s_t = run.translation_sigma_m[i];
    ++tracked;
    if (e_t <= 3.0 * s_t) ++within_3sigma;
    ratio_t.push_back(e_t / s_t);
    sigma_t.push_back(s_t);
    step_t.push_back(e_t);
    frames.push(Json::object()
                    .set("frame", i)
                    .set("translation_sigma_m", s_t)
                    .set("rotation_sigma_deg", run.rotation_sigma_deg[i])
                    .set("step_translation_error_m", e_t)
                    .set("step_rotation_error_deg", rotationAngleDeg(error)));
    previous = i;
  }
  return Json::object()
      .set("what",
           "per tracked frame: the stated sigma (TrackResult) against the error of the motion "
           "from the previous fused frame")
      .set("tracked_frames", tracked)
      .set("translation_sigma_m_median", median(sigma_t))
      .set("step_translation_error_m_median", median(step_t))
      .set("error_over_sigma_median", median(ratio_t))
      .set("share_within_3_sigma", tracked ? static_cast<double>(within_3sigma) / tracked : 0.0)
      .set("frames", frames);
}

MapperConfig mapperConfig(const TrackBenchOptions& o) {
  MapperConfig config;
  if (o.model_level >= 0) config.track.model_level = o.model_level;
  if (o.color_weight >= 0.0) config.track.color_weight = o.color_weight;
  if (!o.iterations.empty()) {
    config.track.iterations = o.iterations;
    config.track.levels = static_cast<int>(o.iterations.size());
  }
  config.validate();
  return config;
}

StrataRun runStrata(const PreloadedFrames& data, const TrackBenchOptions& o) {
  vk::ContextOptions context_options;
  context_options.device_selector = o.device;
  context_options.log_device = false;
  auto context = vk::Context::create(context_options);
  Mapper mapper(mapperConfig(o), *context);
  StrataRun run;
  run.device = context->deviceName();
  run.translation_sigma_m.assign(data.frames.size(), 0.0);
  run.rotation_sigma_deg.assign(data.frames.size(), 0.0);
  for (std::size_t i = 0; i < data.frames.size(); ++i) {
    const TrackedFrame r = mapper.trackAndIntegrate(data.frames[i], data.intrinsics);
    run.T_W_C.push_back(r.track.T_W_C);
    run.fused.push_back(r.fused);
    if (i == 0) continue;  // the first frame is fused at its pose, not tracked
    run.track_ms.push_back(r.track.wall_ms);
    run.device_ms.push_back(r.track.raycast_ms + r.track.equations_ms);
    run.iterations += r.track.iterations;
    run.lowest_eigenvalue = std::min(run.lowest_eigenvalue, r.track.min_eigenvalue);
    run.lowest_inlier_fraction = std::min(run.lowest_inlier_fraction, r.track.inlier_fraction);
    run.highest_rms_m = std::max(run.highest_rms_m, r.track.rms_m);
    run.translation_sigma_m[i] = r.track.translation_sigma_m;
    run.rotation_sigma_deg[i] = r.track.rotation_sigma_deg;
    if (r.fused) run.fusion_ms.push_back(r.integrate.fusion.wall_ms);
    if (!r.fused) ++run.lost;
    if (i % 10 == 0) std::fprintf(stderr, "track: strata frame %zu\n", i);
  }
  run.iterations /= std::max<std::size_t>(1, run.track_ms.size());
  return run;
}

int runChecked(TrackBenchOptions options) {
  if (options.data_dir.empty()) options.data_dir = redkitchenDataDir();
  if (options.frames < 3) throw InputError("--frames must be >= 3");
  const MapperConfig config = mapperConfig(options);  // fail before the slow preload
  const std::string load_at_start = loadAverage();
  const PreloadedFrames data = preloadFrames(options.data_dir, options.frames);
  const StrataRun strata = runStrata(data, options);
  const trajectory::TrajectoryError strata_error = ate(data, strata.T_W_C, strata.fused);
  const double strata_ms = mean(strata.track_ms);
  Json strata_json = Json::object()
                         .set("method",
                              "frame-to-model point-to-plane ICP on the TSDF raycast, "
                              "3-level pyramid, then fusion (docs/track.md)")
                         .set("levels", config.track.levels)
                         .set("model_level", config.track.model_level)
                         .set("lost_frames", strata.lost)
                         .set("tracking_ms_per_frame_mean", strata_ms)
                         .set("tracking_ms_per_frame_median", median(strata.track_ms))
                         .set("tracking_device_ms_per_frame_mean", mean(strata.device_ms))
                         .set("fusion_ms_per_frame_mean", mean(strata.fusion_ms))
                         .set("iterations_per_frame_mean", strata.iterations)
                         .set("lowest_min_eigenvalue", strata.lowest_eigenvalue)
                         .set("lowest_inlier_fraction", strata.lowest_inlier_fraction)
                         .set("highest_rms_m", strata.highest_rms_m)
                         .set("color_weight", config.track.color_weight)
                         .set("uncertainty", uncertaintyJson(data, strata))
                         .set("ate", ateJson(data, strata.T_W_C, strata.fused));

  std::fprintf(stderr, "track: peer odometry\n");
  const PeerTrajectory peer = options.no_peer ? PeerTrajectory{} : runPeerOdometry(data);
  Json peer_json;  // null without the peer
  Json ratios;
  if (peer.available) {
    const trajectory::TrajectoryError peer_error =
        ate(data, peer.T_W_C, std::vector<bool>(data.frames.size(), true));
    const double peer_ms = mean(peer.ms);
    peer_json =
        Json::object()
            .set("peer", peer.peer)
            .set("method", peer.method)
            .set("threads", peer.threads)
            .set("failed_calls", peer.failures)
            .set("ms_per_frame_mean", peer_ms)
            .set("ms_per_frame_median", median(peer.ms))
            .set("ate", ateJson(data, peer.T_W_C, std::vector<bool>(data.frames.size(), true)));
    ratios = Json::object()
                 .set("ate_strata_over_peer", strata_error.ate_rmse_m / peer_error.ate_rmse_m)
                 .set("tracking_ms_strata_over_peer", strata_ms / peer_ms);
  }
  const bool ok = strata_error.ate_rmse_m <= kSelfCheckAte_m;
  Json report =
      Json::object()
          .set("benchmark", "track")
          .set("machine", machineInfo(strata.device, load_at_start))
          .set("data", options.data_dir)
          .set("frames", data.frames.size())
          .set("first_pose", "the dataset's first pose (ATE is SE(3)-aligned anyway)")
          .set("strata", strata_json)
          .set("open3d", peer_json)
          .set("ratios", ratios)
          .set("self_check", Json::object().set("ate_bound_m", kSelfCheckAte_m).set("passed", ok));
  emitReport(report, options.out_path);
  return ok ? 0 : 1;
}

}  // namespace

CLI::App* addTrackCommand(CLI::App& app, TrackBenchOptions& o) {
  CLI::App* track = app.add_subcommand(
      "track", "RGB-D tracking without poses: Strata vs Open3D odometry, ATE and ms per frame");
  o.data_dir = redkitchenDataDir();
  track->add_option("--data", o.data_dir, "TUM RGB-D or 7-Scenes folder")->capture_default_str();
  track->add_option("--frames", o.frames, "Frames from the start")->capture_default_str();
  track->add_option("--out", o.out_path, "Also write the JSON report here");
  track->add_option("--device", o.device, "Vulkan device index or name substring");
  track->add_option("--model-level", o.model_level,
                    "Pyramid level the model is raycast at (default: TrackConfig's)");
  track
      ->add_option("--iterations", o.iterations,
                   "Gauss-Newton iterations per level, the finest level first (sets the level count)")
      ->delimiter(',');
  track->add_option("--color-weight", o.color_weight,
                    "Weight of the photometric term (0: geometry alone; default: TrackConfig's)");
  track->add_flag("--no-peer", o.no_peer, "Skip Open3D's odometry");
  return track;
}

int runTrackBench(const TrackBenchOptions& options) {
  try {
    return runChecked(options);
  } catch (const InputError& e) {
    std::fprintf(stderr, "strata-bench track: input error: %s\n", e.what());
    return 2;
  } catch (const DeviceError& e) {
    std::fprintf(stderr, "strata-bench track: device error: %s\n", e.what());
    return 3;
  }
}

}  // namespace strata::bench
