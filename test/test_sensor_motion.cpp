// Sensor motion models: quintic-spline trajectories, IMU samples, odometry drift.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "strata/core/error.h"
#include "sensor_stats.h"
#include "strata/sim/rng.h"
#include "strata/sim/sensors/imu.h"
#include "strata/sim/sensors/odometry_drift.h"
#include "strata/sim/sensors/quintic_spline.h"
#include "strata/sim/sensors/camera_path.h"

namespace strata::sim {
namespace {

using test::Stats;
using test::statsOf;

std::vector<Waypoint> roomLoop() {
  return {{{0.0, -1.5, 1.4}, {0.0, 1.0, 0.8}},  {{0.8, -1.0, 1.5}, {-0.5, 1.0, 0.6}},
          {{1.3, 0.0, 1.3}, {-1.0, 0.2, 0.7}},  {{0.7, 1.1, 1.6}, {-0.3, -0.8, 0.9}},
          {{-0.6, 1.2, 1.4}, {0.5, -1.0, 0.5}}, {{-1.2, 0.1, 1.2}, {1.0, 0.0, 0.8}}};
}

TEST(SensorTrajectory, QuinticSplineInterpolatesAndStartsAtRest) {
  const auto& M = QuinticBSpline::basisMatrix();
  const double row0[6] = {1, 26, 66, 26, 1, 0};
  for (int j = 0; j < 6; ++j) EXPECT_NEAR(M(0, j), row0[j] / 120.0, 1e-15);
  for (int i = 1; i < 6; ++i) EXPECT_NEAR(M.row(i).sum(), 0.0, 1e-12);  // partition of unity
  std::vector<Eigen::Vector3d> points;
  for (const Waypoint& w : roomLoop()) points.push_back(w.position_W);
  const QuinticBSpline spline(points, 1.7);
  for (std::size_t k = 0; k < points.size(); ++k) {
    EXPECT_NEAR((spline.evaluate(1.7 * k) - points[k]).norm(), 0.0, 1e-12);
  }
  for (double t : {0.0, spline.duration_s()}) {
    EXPECT_NEAR(spline.evaluate(t, 1).norm(), 0.0, 1e-12);
    EXPECT_NEAR(spline.evaluate(t, 2).norm(), 0.0, 1e-12);
  }
}

TEST(SensorTrajectory, DerivativesMatchFiniteDifferences) {
  const Trajectory trajectory(roomLoop(), TrajectoryConfig{}, 3);
  ASSERT_GT(trajectory.duration_s(), 10.0);
  const double h = 1e-4;
  for (double t = 0.3; t < trajectory.duration_s() - 0.3; t += 0.37) {
    const TrajectoryState s = trajectory.state(t);
    const TrajectoryState a = trajectory.state(t - h), b = trajectory.state(t + h);
    const Eigen::Vector3d v_fd = (b.T_W_C.translation() - a.T_W_C.translation()) / (2 * h);
    EXPECT_NEAR((v_fd - s.velocity_W).norm(), 0.0, 1e-6) << t;
    EXPECT_NEAR(((b.velocity_W - a.velocity_W) / (2 * h) - s.acceleration_W).norm(), 0.0, 1e-6);
    // R(t + h) = R(t - h) Exp(2 h w(t)) + O(h^3).
    const Eigen::AngleAxisd delta(a.T_W_C.linear().transpose() * b.T_W_C.linear());
    EXPECT_NEAR((delta.angle() * delta.axis() / (2 * h) - s.angular_velocity_C).norm(), 0.0, 1e-6);
    const Eigen::Vector3d alpha_fd = (b.angular_velocity_C - a.angular_velocity_C) / (2 * h);
    EXPECT_NEAR((alpha_fd - s.angular_acceleration_C).norm(), 0.0, 1e-4) << t;
    EXPECT_LT(s.velocity_W.norm(), 1.5);  // hand-held pace
  }
  EXPECT_EQ(trajectory.sample(30.0).size(), trajectory.sampleTimes(30.0).size());
  EXPECT_THROW(Trajectory({roomLoop()[0]}, TrajectoryConfig{}, 0), InputError);
  EXPECT_THROW(Trajectory({{{0, 0, 1}, {0, 0, 3}}, {{1, 0, 1}, {0, 0, 0}}}, TrajectoryConfig{}, 0),
               InputError);  // looks straight up
}

TEST(SensorTrajectory, RestAtStartHoldsThePoseThenFadesTheSwayInSmoothly) {
  TrajectoryConfig moving;
  TrajectoryConfig resting;
  resting.rest_at_start_s = 2.0;
  const Trajectory path(roomLoop(), moving, 3);
  const Trajectory rest(roomLoop(), resting, 3);
  EXPECT_NEAR(rest.duration_s(), path.duration_s() + 2.0, 1e-12);
  const Eigen::Isometry3d T0 = rest.pose(0.0);
  for (double t = 0.0; t <= 2.0; t += 0.1) {
    const TrajectoryState s = rest.state(t);
    EXPECT_TRUE(s.T_W_C.isApprox(T0, 1e-12)) << t;
    EXPECT_LT(s.velocity_W.norm(), 1e-12) << t;
    EXPECT_LT(s.acceleration_W.norm(), 1e-12) << t;
    if (t < 1.99) {
      EXPECT_LT(s.angular_velocity_C.norm(), 1e-9) << t;
    }
  }
  // After the fade-in the pose is the moving path's, shifted by the rest, minus nothing.
  for (double t = 1.5; t < path.duration_s() - 0.5; t += 0.9) {
    EXPECT_TRUE(rest.pose(t + 2.0).isApprox(path.pose(t), 1e-9)) << t;
  }
  // Through the fade-in the derivatives stay consistent (what the IMU integrates).
  const double h = 1e-4;
  for (double t = 2.05; t < 3.0; t += 0.1) {
    const TrajectoryState s = rest.state(t);
    const TrajectoryState a = rest.state(t - h), b = rest.state(t + h);
    const Eigen::Vector3d v_fd = (b.T_W_C.translation() - a.T_W_C.translation()) / (2 * h);
    EXPECT_NEAR((v_fd - s.velocity_W).norm(), 0.0, 1e-6) << t;
    EXPECT_NEAR(((b.velocity_W - a.velocity_W) / (2 * h) - s.acceleration_W).norm(), 0.0, 1e-6)
        << t;
  }
  resting.rest_at_start_s = -1.0;
  EXPECT_THROW(resting.validate(), InputError);
}

// ---------------------------------------------------------------------------------------------
// IMU

// Integrates noise-free samples with RK4 (dt = sample spacing); the rates at the step midpoint come
// from cubic Lagrange interpolation over four consecutive samples. Returns the final T_W_B.
Eigen::Isometry3d integrateImu(const std::vector<ImuSample>& samples, const Eigen::Isometry3d& T0,
                               Eigen::Vector3d v, double gravity) {
  const auto at = [&](std::size_t k, double s) {  // rates at t_k + s dt, s in [0, 1]
    const std::size_t i = std::clamp<std::size_t>(k, 1, samples.size() - 3) - 1;  // window start
    const double x = static_cast<double>(k - i) + s;                              // in [0, 3]
    Eigen::Matrix<double, 6, 1> r = Eigen::Matrix<double, 6, 1>::Zero();
    for (int j = 0; j < 4; ++j) {
      double w = 1.0;
      for (int m = 0; m < 4; ++m) {
        if (m != j) w *= (x - m) / static_cast<double>(j - m);
      }
      r.head<3>() += w * samples[i + j].gyro_rad_s;
      r.tail<3>() += w * samples[i + j].accel_mps2;
    }
    return r;
  };
  struct State {
    Eigen::Quaterniond q;
    Eigen::Vector3d v, p;
  };
  struct Rate {
    Eigen::Vector4d dq;
    Eigen::Vector3d dv, dp;
  };
  const Eigen::Vector3d g(0, 0, -gravity);
  const auto f = [&](const State& x, const Eigen::Matrix<double, 6, 1>& r) {
    const Eigen::Quaterniond w(0.0, r(0), r(1), r(2));
    // dq/dt = q (x) (0, w) / 2, dv/dt = R f + g, dp/dt = v.
    return Rate{0.5 * (x.q * w).coeffs(), x.q.normalized() * Eigen::Vector3d(r.tail<3>()) + g, x.v};
  };
  const auto step = [](const State& x, const Rate& k, double dt) {
    return State{Eigen::Quaterniond(Eigen::Vector4d(x.q.coeffs() + dt * k.dq)), x.v + dt * k.dv,
                 x.p + dt * k.dp};
  };
  State x{Eigen::Quaterniond(T0.linear()), v, T0.translation()};
  for (std::size_t k = 0; k + 1 < samples.size(); ++k) {
    const double dt = samples[k + 1].t_s - samples[k].t_s;
    const Rate k1 = f(x, at(k, 0.0));
    const Rate k2 = f(step(x, k1, dt / 2), at(k, 0.5));
    const Rate k3 = f(step(x, k2, dt / 2), at(k, 0.5));
    const Rate k4 = f(step(x, k3, dt), at(k, 1.0));
    x.q.coeffs() += dt / 6 * (k1.dq + 2 * k2.dq + 2 * k3.dq + k4.dq);
    x.q.normalize();
    x.v += dt / 6 * (k1.dv + 2 * k2.dv + 2 * k3.dv + k4.dv);
    x.p += dt / 6 * (k1.dp + 2 * k2.dp + 2 * k3.dp + k4.dp);
  }
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = x.q.toRotationMatrix();
  T.translation() = x.p;
  return T;
}

Trajectory tenSecondTrajectory() {
  std::vector<Waypoint> w = roomLoop();
  w.resize(4);
  TrajectoryConfig config;
  config.mean_speed_mps = 0.33;  // three segments of ~3.4 s
  return Trajectory(w, config, 8);
}

TEST(SensorImu, IntegratingNoiseFreeSamplesReproducesTheTrajectory) {
  const Trajectory trajectory = tenSecondTrajectory();
  ASSERT_GE(trajectory.duration_s(), 10.0);
  ASSERT_LT(trajectory.duration_s(), 11.0);
  for (bool lever_arm : {false, true}) {
    ImuConfig config;
    config.noise = false;
    if (lever_arm) {
      config.T_C_B.linear() =
          Eigen::AngleAxisd(0.4, Eigen::Vector3d(1, 2, 3).normalized()).matrix();
      config.T_C_B.translation() = Eigen::Vector3d(0.05, -0.03, 0.02);
    }
    const std::vector<ImuSample> samples = simulateImu(trajectory, config, 1);
    ASSERT_EQ(samples.size(), trajectory.sampleTimes(200.0).size());
    const TrajectoryState s0 = trajectory.state(0.0);
    // Body velocity: v_C + R_W_C (w_C x t_C_B).
    const Eigen::Vector3d v0 =
        s0.velocity_W + s0.T_W_C.linear() * s0.angular_velocity_C.cross(config.T_C_B.translation());
    const Eigen::Isometry3d T_end =
        integrateImu(samples, s0.T_W_C * config.T_C_B, v0, config.gravity_mps2);
    const Eigen::Isometry3d truth = trajectory.pose(samples.back().t_s) * config.T_C_B;
    EXPECT_LT((T_end.translation() - truth.translation()).norm(), 1e-3) << lever_arm;
    EXPECT_LT(Eigen::AngleAxisd(T_end.linear().transpose() * truth.linear()).angle(), 1e-5);
  }
}

TEST(SensorImu, NoiseAndBiasWalkFollowTheDiscreteModel) {
  const Trajectory trajectory = tenSecondTrajectory();
  ImuConfig config;
  config.gyro_random_walk = config.accel_random_walk = 0.0;
  config.initial_gyro_bias = Eigen::Vector3d(0.01, -0.02, 0.03);
  const std::vector<ImuSample> noisy = simulateImu(trajectory, config, 21);
  config.noise = false;
  const std::vector<ImuSample> exact = simulateImu(trajectory, config, 21);
  std::vector<double> gyro_errors, accel_errors;
  for (std::size_t k = 0; k < noisy.size(); ++k) {
    for (int a = 0; a < 3; ++a) {
      gyro_errors.push_back(noisy[k].gyro_rad_s[a] - exact[k].gyro_rad_s[a]);
      accel_errors.push_back(noisy[k].accel_mps2[a] - exact[k].accel_mps2[a]);
    }
  }
  const double sqrt_dt = std::sqrt(1.0 / config.rate_hz);
  EXPECT_NEAR(statsOf(gyro_errors).stddev / (ImuConfig{}.gyro_noise_density / sqrt_dt), 1.0, 0.05);
  EXPECT_NEAR(statsOf(accel_errors).stddev / (ImuConfig{}.accel_noise_density / sqrt_dt), 1.0,
              0.05);
  EXPECT_NEAR((exact[7].gyro_bias - config.initial_gyro_bias).norm(), 0.0, 1e-15);

  ImuConfig walk;
  walk.gyro_noise_density = walk.accel_noise_density = 0.0;
  const std::vector<ImuSample> walked = simulateImu(trajectory, walk, 22);
  std::vector<double> steps;
  for (std::size_t k = 1; k < walked.size(); ++k) {
    for (int a = 0; a < 3; ++a)
      steps.push_back(walked[k].accel_bias[a] - walked[k - 1].accel_bias[a]);
  }
  EXPECT_NEAR(statsOf(steps).stddev / (walk.accel_random_walk * sqrt_dt), 1.0, 0.05);
}

TEST(SensorImu, EurocCsvHeaderAndRows) {
  const Trajectory trajectory = tenSecondTrajectory();
  ImuConfig config;
  config.start_time_ns = 1403636579758555392LL;  // an EuRoC-like epoch
  const std::vector<ImuSample> samples = simulateImu(trajectory, config, 3);
  const std::string path = (std::filesystem::temp_directory_path() /
                            ("strata_imu_" + std::to_string(::getpid()) + ".csv"))
                               .string();
  writeImuCsv(path, samples);
  std::ifstream in(path);
  std::string line;
  std::getline(in, line);
  EXPECT_EQ(line,
            "#timestamp [ns],w_RS_S_x [rad s^-1],w_RS_S_y [rad s^-1],w_RS_S_z [rad s^-1],"
            "a_RS_S_x [m s^-2],a_RS_S_y [m s^-2],a_RS_S_z [m s^-2]");
  std::size_t rows = 0;
  while (std::getline(in, line)) {
    if (rows == 1) {
      EXPECT_EQ(line.substr(0, line.find(',')), "1403636579763555392");  // +5 ms
    }
    EXPECT_EQ(std::count(line.begin(), line.end(), ','), 6);
    ++rows;
  }
  EXPECT_EQ(rows, samples.size());
  std::filesystem::remove(path);
}

// ---------------------------------------------------------------------------------------------
// Odometry drift

TEST(SensorDrift, RandomWalkGrowsWithDistanceAndKeepsRollPitch) {
  std::vector<Eigen::Isometry3d> truth;
  for (int k = 0; k <= 100; ++k) {  // 10 m straight line, 0.1 m steps
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.translation() = Eigen::Vector3d(0.1 * k, 0.0, 1.0);
    truth.push_back(T);
  }
  const DriftConfig config;
  EXPECT_EQ(addOdometryDrift(truth, DriftConfig{0.0, 0.0}, 1).back().matrix(),
            truth.back().matrix());
  std::vector<double> z_errors, yaw_errors;
  for (std::uint64_t seed = 0; seed < 400; ++seed) {
    const std::vector<Eigen::Isometry3d> drifted = addOdometryDrift(truth, config, seed);
    ASSERT_EQ(drifted.front().matrix(), truth.front().matrix());
    const Eigen::Matrix3d dR = drifted.back().linear() * truth.back().linear().transpose();
    ASSERT_NEAR(dR(2, 2), 1.0, 1e-12);  // pure yaw
    yaw_errors.push_back(std::atan2(dR(1, 0), dR(0, 0)));
    z_errors.push_back(drifted.back().translation().z() - 1.0);
  }
  // After L = 10 m: sigma = sigma_per_sqrt_m * sqrt(L); 400 draws estimate it to ~3.5 %.
  EXPECT_NEAR(statsOf(z_errors).stddev / (config.translation_sigma_m_per_sqrt_m * std::sqrt(10.0)),
              1.0, 0.15);
  EXPECT_NEAR(statsOf(yaw_errors).stddev / (config.yaw_sigma_rad_per_sqrt_m * std::sqrt(10.0)), 1.0,
              0.15);
  EXPECT_EQ(addOdometryDrift(truth, config, 5).back().matrix(),
            addOdometryDrift(truth, config, 5).back().matrix());
}

}  // namespace
}  // namespace strata::sim
