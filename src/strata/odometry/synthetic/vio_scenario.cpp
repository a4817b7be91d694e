#include "strata/odometry/synthetic/vio_scenario.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <random>

namespace strata::odometry::synthetic {
namespace {

std::vector<Eigen::Vector3d> roomLandmarks(int count, std::mt19937_64& rng) {
  // Walls, floor and ceiling of a 8 x 8 x 3.5 m room around the trajectory.
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::uniform_int_distribution<int> face(0, 5);
  std::vector<Eigen::Vector3d> points;
  for (int i = 0; i < count; ++i) {
    const int f = face(rng);
    Eigen::Vector3d p(4.0 * u(rng), 4.0 * u(rng), 1.75 + 1.75 * u(rng));
    if (f == 0) p.x() = -4.0;
    if (f == 1) p.x() = 4.0;
    if (f == 2) p.y() = -4.0;
    if (f == 3) p.y() = 4.0;
    if (f == 4) p.z() = 0.0;
    if (f == 5) p.z() = 3.5;
    points.push_back(p);
  }
  return points;
}

Eigen::Vector3d gaussian3(std::mt19937_64& rng) {
  std::normal_distribution<double> n(0.0, 1.0);
  return {n(rng), n(rng), n(rng)};
}

}  // namespace

sim::Trajectory roomTrajectory() {
  const std::vector<sim::Waypoint> w = {{{0.0, -1.5, 1.4}, {0.0, 1.0, 0.8}},
                                        {{0.8, -1.0, 1.5}, {-0.5, 1.0, 0.6}},
                                        {{1.3, 0.0, 1.3}, {-1.0, 0.2, 0.7}},
                                        {{0.7, 1.1, 1.6}, {-0.3, -0.8, 0.9}}};
  sim::TrajectoryConfig config;
  config.mean_speed_mps = 0.33;
  return sim::Trajectory(w, config, 8);
}

CameraRig stereoRig() {
  CameraRig rig;
  rig.T_B_Cl.linear() = Eigen::AngleAxisd(0.3, Eigen::Vector3d(1, -2, 1).normalized()).matrix();
  rig.T_B_Cl.translation() = Eigen::Vector3d(0.02, -0.06, 0.01);
  rig.right = rig.left;
  rig.T_B_Cr = rig.T_B_Cl * Eigen::Translation3d(0.11, 0.0, 0.0);
  return rig;
}

Scenario makeScenario(const ScenarioConfig& c) {
  Scenario s;
  s.rig = stereoRig();
  const sim::Trajectory trajectory = roomTrajectory();
  sim::ImuConfig imu = c.imu;
  imu.T_C_B = s.rig.T_B_Cl.inverse();
  std::mt19937_64 rng(c.seed);
  // The body rests at the trajectory's first pose, then follows it.
  auto stateAt = [&](double t) {
    sim::TrajectoryState st = trajectory.state(std::max(t - c.standstill_s, 0.0));
    if (t < c.standstill_s) {
      st.velocity_W.setZero();
      st.acceleration_W.setZero();
      st.angular_velocity_C.setZero();
      st.angular_acceleration_C.setZero();
    }
    return st;
  };
  const double duration = c.standstill_s + trajectory.duration_s();
  const double dt = 1.0 / imu.rate_hz;
  const double gyro_sigma = imu.noise ? imu.gyro_noise_density / std::sqrt(dt) : 0.0;
  const double accel_sigma = imu.noise ? imu.accel_noise_density / std::sqrt(dt) : 0.0;
  const double gyro_walk = imu.noise ? imu.gyro_random_walk * std::sqrt(dt) : 0.0;
  const double accel_walk = imu.noise ? imu.accel_random_walk * std::sqrt(dt) : 0.0;
  Eigen::Vector3d bg = imu.initial_gyro_bias, ba = imu.initial_accel_bias;
  for (int k = 0; k * dt <= duration; ++k) {
    sim::ImuSample sample;
    sample.t_s = k * dt;
    sim::idealImu(stateAt(sample.t_s), imu, &sample.gyro_rad_s, &sample.accel_mps2);
    sample.gyro_bias = bg;
    sample.accel_bias = ba;
    s.imu_truth.push_back(sample);
    ImuMeasurement m;
    m.t_s = sample.t_s;
    m.gyro_rad_s = sample.gyro_rad_s + bg + gyro_sigma * gaussian3(rng);
    m.accel_mps2 = sample.accel_mps2 + ba + accel_sigma * gaussian3(rng);
    s.imu.push_back(m);
    bg += gyro_walk * gaussian3(rng);
    ba += accel_walk * gaussian3(rng);
  }

  const std::vector<Eigen::Vector3d> points = roomLandmarks(c.landmarks, rng);
  std::vector<double> priority(points.size());
  std::uniform_real_distribution<double> u01(0.0, 1.0);
  for (double& p : priority) p = u01(rng);
  std::normal_distribution<double> pixel(0.0, c.pixel_noise_px);
  const Eigen::Isometry3d T_Cl_Cr = s.rig.T_B_Cl.inverse() * s.rig.T_B_Cr;
  for (int f = 0; f / c.camera_rate_hz <= duration; ++f) {
    const double t = f / c.camera_rate_hz;
    const sim::TrajectoryState st = stateAt(t);
    const Eigen::Isometry3d T_W_C = st.T_W_C;
    const Eigen::Isometry3d T_W_B = T_W_C * imu.T_C_B;
    s.T_W_C_truth.push_back(T_W_C);
    s.T_W_B_truth.push_back(T_W_B);
    s.v_W_B_truth.push_back(st.velocity_W +
                            T_W_C.linear() * st.angular_velocity_C.cross(imu.T_C_B.translation()));
    std::vector<std::pair<double, FeatureObservation>> visible;
    auto inImage = [&](const Eigen::Vector2d& uv) {
      return uv.x() > 2 && uv.y() > 2 && uv.x() < s.rig.left.width_px - 3 &&
             uv.y() < s.rig.left.height_px - 3;
    };
    for (std::size_t i = 0; i < points.size(); ++i) {
      const Eigen::Vector3d p_Cl = T_W_C.inverse() * points[i];
      const Eigen::Vector3d p_Cr = T_Cl_Cr.inverse() * p_Cl;
      if (p_Cl.z() < 0.3 || p_Cr.z() < 0.3) continue;
      FeatureObservation o;
      o.track_id = i;
      o.uv_left_px = s.rig.left.project(p_Cl) + Eigen::Vector2d(pixel(rng), pixel(rng));
      o.xy_left_norm = s.rig.left.unproject(o.uv_left_px).head<2>();
      const Eigen::Vector2d uv_r =
          s.rig.right->project(p_Cr) + Eigen::Vector2d(pixel(rng), pixel(rng));
      if (!inImage(o.uv_left_px)) continue;
      if (inImage(uv_r)) {  // no distortion: raw pixels are the pinhole model's
        o.uv_right_px = uv_r;
        o.xy_right_norm = s.rig.right->unproject(uv_r).head<2>();
      }
      visible.push_back({priority[i], o});
    }
    std::sort(visible.begin(), visible.end(),
              [](const auto& a, const auto& b) { return a.first < b.first; });
    FrameObservations frame;
    frame.t_s = t;
    for (std::size_t i = 0; i < visible.size() && static_cast<int>(i) < c.max_features; ++i) {
      frame.features.push_back(visible[i].second);
    }
    s.frames.push_back(frame);
  }
  return s;
}

}  // namespace strata::odometry::synthetic
