#include "strata/repeat/teach_recording.h"

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "strata/core/error.h"
#include "strata/explore/exploration_loop.h"
#include "strata/io/tum_writer.h"
#include "strata/store/session_store.h"

namespace strata::repeat {
namespace {

namespace fs = std::filesystem;

/// The flight's states at the camera rate (the last state always included).
std::vector<FlightState> framesOf(const std::vector<FlightState>& flight, double rate_hz) {
  std::vector<FlightState> frames;
  double next_s = 0.0;
  for (const FlightState& s : flight) {
    if (s.t_s + 1e-9 < next_s) continue;
    frames.push_back(s);
    next_s += 1.0 / rate_hz;
  }
  if (!flight.empty() && frames.back().t_s != flight.back().t_s) frames.push_back(flight.back());
  return frames;
}

/// Frames are stamped from this time on (seconds), as recordings rarely start at zero.
constexpr double kFirstTimestampS = 1.0;

}  // namespace

sim::Lighting sessionLighting(const sim::World& world, int session) {
  const sim::Light& light = world.session(session).light;
  sim::Lighting lighting;
  lighting.direction_W = light.direction_W.normalized();
  lighting.intensity = light.intensity;
  lighting.ambient = light.ambient;
  return lighting;
}

sim::RgbdCameraConfig CameraSetup::config() const {
  validate();
  sim::RgbdCameraConfig c;
  const float f = static_cast<float>(0.5 * width_px / std::tan(0.5 * horizontal_fov_rad));
  c.intrinsics = {width_px, height_px, f, f, 0.5f * (width_px - 1), 0.5f * (height_px - 1)};
  c.min_range_m = min_range_m;
  c.max_range_m = max_range_m;
  if (texture) {
    sim::WorldTextureConfig t;
    t.coarse_cell_m *= texture_scale;
    t.fine_cell_m *= texture_scale;
    t.contrast = texture_contrast;
    c.color_texture = t;
  }
  return c;
}

void CameraSetup::validate() const {
  if (width_px < 32 || height_px < 24 || width_px > 4096 || height_px > 4096) {
    throw InputError("camera image must be 32x24 to 4096x4096 pixels");
  }
  if (!(horizontal_fov_rad > 0.2 && horizontal_fov_rad < 2.8)) {
    throw InputError("camera horizontal field of view must be in (0.2, 2.8) rad");
  }
  if (!(min_range_m > 0.0 && max_range_m > min_range_m && std::isfinite(max_range_m))) {
    throw InputError("camera ranges: need 0 < min < max");
  }
  if (!(texture_contrast >= 0.0 && texture_contrast <= 1.0)) {
    throw InputError("camera texture_contrast must be in [0, 1]");
  }
  if (!(texture_scale > 0.0 && texture_scale <= 100.0)) {
    throw InputError("camera texture_scale must be in (0, 100]");
  }
}

sim::DriftConfig TeachConfig::defaultDrift() {
  sim::DriftConfig d;
  d.translation_sigma_m_per_sqrt_m = 0.025;
  d.yaw_sigma_rad_per_sqrt_m = 0.01;
  return d;
}

void TeachConfig::validate() const {
  route.validate();
  camera.validate();
  drift.validate();
  if (!(camera_rate_hz > 0.0 && camera_rate_hz <= 100.0)) {
    throw InputError("camera rate must be in (0, 100] Hz");
  }
  if (session < 0) throw InputError("teach session must be >= 0");
  if (keyframe_every < 1) throw InputError("keyframe_every must be >= 1");
}

TeachResult recordTeach(const sim::World& world, const TeachConfig& config, const std::string& dir,
                        const TeachProgress& progress) {
  config.validate();
  world.session(config.session);  // InputError for a session the world lacks
  const std::unique_ptr<sim::WorldScene> scene = world.buildScene(config.session);
  TeachResult result;
  result.waypoints_W = routeWaypoints(world, config.route);
  const std::vector<FlightState> flight = flyRoute(result.waypoints_W, *scene, config.route);
  const std::vector<FlightState> frames = framesOf(flight, config.camera_rate_hz);
  result.duration_s = flight.back().t_s;
  std::vector<Eigen::Isometry3d> true_T_W_C;
  for (const FlightState& s : frames) {
    true_T_W_C.push_back(explore::cameraPose({s.p_W, s.yaw_rad}, 0.0f));
  }
  for (std::size_t i = 1; i < flight.size(); ++i) {
    result.length_m += (flight[i].p_W - flight[i - 1].p_W).norm();
  }
  const std::vector<Eigen::Isometry3d> odometry_T_W_C =
      sim::addOdometryDrift(true_T_W_C, config.drift, config.seed * 7919u + 17u);

  fs::create_directories(dir);
  const sim::RgbdCamera camera(config.camera.config());
  const sim::Lighting lighting = sessionLighting(world, config.session);
  TumWriter writer(dir, camera.config().intrinsics, camera.config().depth_scale);
  for (std::size_t i = 0; i < frames.size(); ++i) {
    const double t = kFirstTimestampS + frames[i].t_s;
    sim::SimulatedFrame frame =
        camera.render(*scene, true_T_W_C[i], lighting, config.seed * 1000003u + i);
    writer.add(
        sim::makeRgbdFrame(std::move(frame), true_T_W_C[i], t, "teach-" + std::to_string(i)));
    result.truth.push_back({t, true_T_W_C[i]});
    result.odometry.push_back({t, odometry_T_W_C[i]});
    const double drift = (odometry_T_W_C[i].translation() - true_T_W_C[i].translation()).norm();
    result.max_drift_m = std::max(result.max_drift_m, drift);
    result.final_drift_m = drift;
    if (progress) progress(i + 1, frames.size());
  }
  writer.finish();
  writeTumTrajectory((fs::path(dir) / "odometry.txt").string(), result.odometry,
                     {"odometry of the teach (drifted); groundtruth.txt holds the truth",
                      "timestamp tx ty tz qx qy qz qw (camera-to-world)"});
  writeTumTrajectory((fs::path(dir) / kTaughtPathFile).string(), result.odometry,
                     {"the taught path as the map believes it (map frame = teach odometry)",
                      "timestamp tx ty tz qx qy qz qw (camera-to-map)"});
  store::Store db((fs::path(dir) / kMapFile).string());
  store::ImportOptions import;
  import.keyframe_every = config.keyframe_every;
  result.import = store::importTumSession(db, fs::absolute(dir).string(), import);
  return result;
}

}  // namespace strata::repeat
