// IMU preintegration (Forster et al. TRO 2017), the IMU factor, marginalisation and the
// initialisers, on the simulator's IMU.
#include <ceres/autodiff_cost_function.h>
#include <gtest/gtest.h>

#include <random>
#include <vector>

#include "strata/odometry/imu_factor.h"
#include "strata/odometry/initialization.h"
#include "strata/odometry/marginalization.h"
#include "strata/odometry/preintegration.h"
#include "strata/odometry/reprojection_factor.h"
#include "strata/odometry/so3.h"
#include "strata/odometry/synthetic/vio_scenario.h"
#include "strata/sim/sensors/imu.h"

namespace strata::odometry {
namespace {

std::vector<ImuMeasurement> toMeasurements(const std::vector<sim::ImuSample>& samples) {
  std::vector<ImuMeasurement> out;
  for (const sim::ImuSample& s : samples) out.push_back({s.t_s, s.gyro_rad_s, s.accel_mps2});
  return out;
}

struct BodyState {
  Eigen::Matrix3d R;
  Eigen::Vector3d p, v;
};

BodyState bodyState(const sim::Trajectory& trajectory, const sim::ImuConfig& config, double t) {
  const sim::TrajectoryState s = trajectory.state(t);
  const Eigen::Isometry3d T_W_B = s.T_W_C * config.T_C_B;
  return {T_W_B.linear(), T_W_B.translation(),
          s.velocity_W + s.T_W_C.linear() * s.angular_velocity_C.cross(config.T_C_B.translation())};
}

sim::ImuConfig leverArmConfig() {
  sim::ImuConfig config;
  config.noise = false;
  config.T_C_B.linear() = Eigen::AngleAxisd(0.4, Eigen::Vector3d(1, 2, 3).normalized()).matrix();
  config.T_C_B.translation() = Eigen::Vector3d(0.05, -0.03, 0.02);
  return config;
}

TEST(Preintegration, IdealImuMatchesTheTrueRelativeMotion) {
  const sim::Trajectory trajectory = synthetic::roomTrajectory();
  const sim::ImuConfig config = leverArmConfig();
  const std::vector<ImuMeasurement> samples =
      toMeasurements(sim::simulateImu(trajectory, config, 1));
  const Eigen::Vector3d g(0.0, 0.0, -config.gravity_mps2);
  double worst_rot = 0.0, worst_v = 0.0, worst_p = 0.0;
  for (double t0 = 0.3; t0 + 0.5 < trajectory.duration_s(); t0 += 0.7) {
    const double t1 = t0 + 0.5;  // ten 20 Hz frames
    Preintegration pre(ImuBias{}, ImuNoise{});
    pre.integrateInterval(samples, t0, t1);
    EXPECT_NEAR(pre.dt_s(), 0.5, 1e-12);
    const BodyState a = bodyState(trajectory, config, t0), b = bodyState(trajectory, config, t1);
    Eigen::Matrix3d R;
    Eigen::Vector3d p, v;
    pre.predict(a.R, a.p, a.v, ImuBias{}, g, &R, &p, &v);
    worst_rot = std::max(worst_rot, logSO3(R.transpose() * b.R).norm());
    worst_v = std::max(worst_v, (v - b.v).norm());
    worst_p = std::max(worst_p, (p - b.p).norm());
  }
  // Midpoint integration at 200 Hz of a smooth hand-held motion.
  EXPECT_LT(worst_rot, 1e-5);
  EXPECT_LT(worst_v, 2e-4);
  EXPECT_LT(worst_p, 5e-5);
}

TEST(Preintegration, BiasJacobiansMatchReintegrationForSmallBiasChanges) {
  const sim::Trajectory trajectory = synthetic::roomTrajectory();
  const std::vector<ImuMeasurement> samples =
      toMeasurements(sim::simulateImu(trajectory, leverArmConfig(), 1));
  Preintegration pre(ImuBias{}, ImuNoise{});
  pre.integrateInterval(samples, 2.0, 2.5);
  ImuBias moved;
  moved.gyro_rad_s = Eigen::Vector3d(0.004, -0.003, 0.005);
  moved.accel_mps2 = Eigen::Vector3d(0.05, 0.04, -0.06);
  Preintegration again = pre;
  again.reintegrate(moved);
  // The change the bias makes, and how much of it the first-order correction misses.
  const double dR_change = logSO3(pre.deltaR().transpose() * again.deltaR()).norm();
  const double dR_miss = logSO3(pre.correctedDeltaR(moved).transpose() * again.deltaR()).norm();
  const double dv_change = (again.deltaV() - pre.deltaV()).norm();
  const double dv_miss = (pre.correctedDeltaV(moved) - again.deltaV()).norm();
  const double dp_change = (again.deltaP() - pre.deltaP()).norm();
  const double dp_miss = (pre.correctedDeltaP(moved) - again.deltaP()).norm();
  EXPECT_GT(dR_change, 1e-3);
  EXPECT_LT(dR_miss, 1e-3 * dR_change);
  EXPECT_GT(dv_change, 1e-2);
  EXPECT_LT(dv_miss, 1e-2 * dv_change);
  EXPECT_LT(dp_miss, 1e-2 * dp_change);
  // Re-integration with the same bias changes nothing.
  Preintegration same = pre;
  same.reintegrate(ImuBias{});
  EXPECT_LT((same.deltaP() - pre.deltaP()).norm(), 1e-15);
}

TEST(Preintegration, CovarianceMatchesMonteCarlo) {
  const sim::Trajectory trajectory = synthetic::roomTrajectory();
  const std::vector<ImuMeasurement> exact =
      toMeasurements(sim::simulateImu(trajectory, leverArmConfig(), 1));
  const ImuNoise noise;
  const double dt = 1.0 / 200.0;
  const double t0 = 3.0, t1 = 3.5;
  Preintegration truth(ImuBias{}, noise);
  truth.integrateInterval(exact, t0, t1);
  std::mt19937_64 rng(99);
  std::normal_distribution<double> n(0.0, 1.0);
  const int trials = 400;
  Eigen::Matrix<double, 9, 9> sample_cov = Eigen::Matrix<double, 9, 9>::Zero();
  for (int trial = 0; trial < trials; ++trial) {
    std::vector<ImuMeasurement> noisy = exact;
    for (ImuMeasurement& m : noisy) {
      for (int a = 0; a < 3; ++a) {
        m.gyro_rad_s[a] += noise.gyro_noise_density / std::sqrt(dt) * n(rng);
        m.accel_mps2[a] += noise.accel_noise_density / std::sqrt(dt) * n(rng);
      }
    }
    Preintegration pre(ImuBias{}, noise);
    pre.integrateInterval(noisy, t0, t1);
    Eigen::Matrix<double, 9, 1> e;
    e << logSO3(truth.deltaR().transpose() * pre.deltaR()), pre.deltaV() - truth.deltaV(),
        pre.deltaP() - truth.deltaP();
    sample_cov += e * e.transpose() / trials;
  }
  // Per block (rotation, velocity, position): the traces agree within the Monte-Carlo spread.
  for (int block = 0; block < 3; ++block) {
    const double predicted = truth.covariance().block<3, 3>(3 * block, 3 * block).trace();
    const double measured = sample_cov.block<3, 3>(3 * block, 3 * block).trace();
    EXPECT_GT(measured / predicted, 0.8) << "block " << block;
    EXPECT_LT(measured / predicted, 1.25) << "block " << block;
  }
}

TEST(ImuFactor, ZeroAtTruthAndWhitenedByTheCovariance) {
  const sim::Trajectory trajectory = synthetic::roomTrajectory();
  const sim::ImuConfig config = leverArmConfig();
  const std::vector<ImuMeasurement> samples =
      toMeasurements(sim::simulateImu(trajectory, config, 1));
  auto pre = std::make_shared<Preintegration>(ImuBias{}, ImuNoise{});
  pre->integrateInterval(samples, 4.0, 4.5);
  const BodyState a = bodyState(trajectory, config, 4.0), b = bodyState(trajectory, config, 4.5);
  auto pose = [](const BodyState& s, double* out) {
    const Eigen::Quaterniond q(s.R);
    out[0] = q.x(), out[1] = q.y(), out[2] = q.z(), out[3] = q.w();
    for (int k = 0; k < 3; ++k) out[4 + k] = s.p[k];
  };
  double pose_i[7], pose_j[7], sb_i[9] = {}, sb_j[9] = {};
  pose(a, pose_i);
  pose(b, pose_j);
  for (int k = 0; k < 3; ++k) sb_i[k] = a.v[k], sb_j[k] = b.v[k];
  std::unique_ptr<ceres::CostFunction> f(
      ImuFactor::create(pre, Eigen::Vector3d(0, 0, -config.gravity_mps2)));
  const double* params[] = {pose_i, sb_i, pose_j, sb_j};
  Eigen::Matrix<double, 15, 1> r;
  ASSERT_TRUE(f->Evaluate(params, r.data(), nullptr));
  EXPECT_LT(r.norm(), 0.05);  // integration error far below one sigma
  // A 1 mm position error at j is ~1 mm / sigma_p in the whitened residual.
  pose_j[4] += 1e-3;
  ASSERT_TRUE(f->Evaluate(params, r.data(), nullptr));
  const double sigma_px = std::sqrt(pre->covariance()(6, 6));
  EXPECT_GT(r.norm(), 0.3 * 1e-3 / sigma_px);
  // The accelerometer bias shifts dv by dv/dba dba: the residual follows the Jacobian.
  pose_j[4] -= 1e-3;
  sb_i[6] = 0.01;
  ASSERT_TRUE(f->Evaluate(params, r.data(), nullptr));
  EXPECT_GT(r.segment<3>(3).norm(), 1.0);
}

TEST(ReprojectionCost, AnalyticJacobiansMatchAutoDiff) {
  const CameraRig rig = synthetic::stereoRig();
  std::mt19937_64 rng(11);
  std::normal_distribution<double> n(0.0, 1.0);
  int compared = 0;
  for (int trial = 0; trial < 40; ++trial) {
    double pose_a[7], pose_j[7];
    for (double* pose : {pose_a, pose_j}) {
      Eigen::Quaterniond q(n(rng), n(rng), n(rng), n(rng));
      q.normalize();
      pose[0] = q.x(), pose[1] = q.y(), pose[2] = q.z(), pose[3] = q.w();
      for (int k = 4; k < 7; ++k) pose[k] = 0.1 * n(rng);
    }
    // A point 2-4 m in front of camera a, observed wherever it lands in camera j.
    const Eigen::Vector3d bearing(0.2 * n(rng), 0.2 * n(rng), 1.0);
    double rho = 1.0 / (3.0 + n(rng) * 0.3);
    const Eigen::Vector2d uv(300.0 + 10.0 * n(rng), 200.0 + 10.0 * n(rng));
    const bool right = trial % 2 == 1;
    const ReprojectionCost analytic(bearing, rig.T_B_Cl, right ? rig.T_B_Cr : rig.T_B_Cl, rig.left,
                                    uv, 0.8);
    std::unique_ptr<ceres::CostFunction> reference(ReprojectionFactor::create(
        bearing, rig.T_B_Cl, right ? rig.T_B_Cr : rig.T_B_Cl, rig.left, uv, 0.8));
    const double* params[] = {pose_a, pose_j, &rho};
    double r1[2], r2[2], ja1[14], jj1[14], jr1[2], ja2[14], jj2[14], jr2[2];
    double* jac1[] = {ja1, jj1, jr1};
    double* jac2[] = {ja2, jj2, jr2};
    const bool ok1 = analytic.Evaluate(params, r1, jac1);
    const bool ok2 = reference->Evaluate(params, r2, jac2);
    ASSERT_EQ(ok1, ok2);
    if (!ok1) continue;  // behind camera j: both refuse
    ++compared;
    for (int i = 0; i < 2; ++i) EXPECT_NEAR(r1[i], r2[i], 1e-9 * (1.0 + std::abs(r2[i])));
    for (int i = 0; i < 14; ++i) {
      EXPECT_NEAR(ja1[i], ja2[i], 1e-7 * (1.0 + std::abs(ja2[i]))) << trial << " a " << i;
      EXPECT_NEAR(jj1[i], jj2[i], 1e-7 * (1.0 + std::abs(jj2[i]))) << trial << " j " << i;
    }
    for (int i = 0; i < 2; ++i) EXPECT_NEAR(jr1[i], jr2[i], 1e-7 * (1.0 + std::abs(jr2[i])));
  }
  EXPECT_GE(compared, 10);
}

// Linear residuals r = A x - b on two 2-vectors: marginalising x1 must give the Schur complement.
struct LinearResidual {
  Eigen::Matrix<double, 3, 4> A;
  Eigen::Vector3d b;
  template <typename T>
  bool operator()(const T* x1, const T* x2, T* r) const {
    for (int i = 0; i < 3; ++i) {
      r[i] = A(i, 0) * x1[0] + A(i, 1) * x1[1] + A(i, 2) * x2[0] + A(i, 3) * x2[1] - b[i];
    }
    return true;
  }
};

TEST(Marginalisation, GivesTheSchurComplementOfALinearSystem) {
  std::mt19937_64 rng(3);
  std::normal_distribution<double> n(0.0, 1.0);
  double x1[2] = {0.3, -0.2}, x2[2] = {0.1, 0.4};
  std::vector<std::unique_ptr<ceres::CostFunction>> costs;
  std::vector<LinearisedFactor> factors;
  Eigen::Matrix4d H = Eigen::Matrix4d::Zero();
  Eigen::Vector4d g = Eigen::Vector4d::Zero();
  for (int k = 0; k < 3; ++k) {
    auto* functor = new LinearResidual;
    for (int i = 0; i < 12; ++i) functor->A.data()[i] = n(rng);
    functor->b = Eigen::Vector3d(n(rng), n(rng), n(rng));
    const Eigen::Vector4d x(x1[0], x1[1], x2[0], x2[1]);
    const Eigen::Vector3d r = functor->A * x - functor->b;
    H += functor->A.transpose() * functor->A;
    g += functor->A.transpose() * r;
    costs.emplace_back(new ceres::AutoDiffCostFunction<LinearResidual, 3, 2, 2>(functor));
    factors.push_back({costs.back().get(), nullptr, {x1, x2}});
  }
  const std::unique_ptr<LinearPrior> prior = marginalise(factors, {x1}, {});
  ASSERT_TRUE(prior);
  ASSERT_EQ(prior->blocks().size(), 1u);
  const Eigen::Matrix2d Hs = H.bottomRightCorner<2, 2>() - H.bottomLeftCorner<2, 2>() *
                                                               H.topLeftCorner<2, 2>().inverse() *
                                                               H.topRightCorner<2, 2>();
  const Eigen::MatrixXd J = prior->jacobian();
  EXPECT_LT((J.transpose() * J - Hs).norm(), 1e-9 * Hs.norm());
  // The prior's minimum is where x2 minimises the full problem with x1 eliminated.
  const Eigen::Vector4d x_opt = Eigen::Vector4d(x1[0], x1[1], x2[0], x2[1]) - H.ldlt().solve(g);
  Eigen::Vector2d r;
  const double x2_opt[2] = {x_opt[2], x_opt[3]};
  const double* params[] = {x2_opt};
  ASSERT_TRUE(prior->Evaluate(params, r.data(), nullptr));
  EXPECT_LT(r.norm(), 1e-9);
}

TEST(Initialisation, StandstillRecoversGravityDirectionAndGyroBias) {
  synthetic::ScenarioConfig config;
  config.standstill_s = 1.0;
  config.imu.initial_gyro_bias = Eigen::Vector3d(0.004, -0.006, 0.003);
  const synthetic::Scenario s = synthetic::makeScenario(config);
  const std::optional<InitialState> init = initializeFromStandstill(s.imu, 0.9, StandstillConfig{});
  ASSERT_TRUE(init);
  const Eigen::Matrix3d R_true = s.T_W_B_truth[0].linear();
  const Eigen::Vector3d up_est = init->R_W_B.transpose() * Eigen::Vector3d::UnitZ();
  const Eigen::Vector3d up_true = R_true.transpose() * Eigen::Vector3d::UnitZ();
  EXPECT_LT(std::acos(std::min(1.0, up_est.dot(up_true))), 1.0 * M_PI / 180.0);
  EXPECT_LT((init->bias.gyro_rad_s - config.imu.initial_gyro_bias).norm(), 1e-3);
  // Moving: refused.
  EXPECT_FALSE(initializeFromStandstill(s.imu, 3.0, StandstillConfig{}));
}

TEST(Initialisation, InMotionAlignmentRecoversBiasGravityAndVelocity) {
  synthetic::ScenarioConfig config;
  config.standstill_s = 0.0;
  config.imu.noise = false;
  config.imu.initial_gyro_bias = Eigen::Vector3d(0.01, -0.02, 0.015);
  const synthetic::Scenario s = synthetic::makeScenario(config);
  // Eight 20 Hz frames from t = 3 s, in a vision frame rotated and shifted away from W.
  Eigen::Isometry3d T_V_W = Eigen::Isometry3d::Identity();
  T_V_W.linear() = Eigen::AngleAxisd(0.7, Eigen::Vector3d(0.3, 1.0, -0.2).normalized()).matrix();
  T_V_W.translation() = Eigen::Vector3d(1.0, 2.0, -0.5);
  std::vector<Eigen::Isometry3d> T_V_B;
  std::vector<Preintegration> pre;
  for (int f = 60; f < 68; ++f) {
    T_V_B.push_back(T_V_W * s.T_W_B_truth[static_cast<std::size_t>(f)]);
    if (f > 60) {
      pre.emplace_back(ImuBias{}, ImuNoise{});
      pre.back().integrateInterval(s.imu, s.frames[static_cast<std::size_t>(f) - 1].t_s,
                                   s.frames[static_cast<std::size_t>(f)].t_s);
    }
  }
  const std::optional<AlignmentResult> a = alignVisualInertial(T_V_B, &pre, 9.81);
  ASSERT_TRUE(a);
  EXPECT_LT((a->gyro_bias - config.imu.initial_gyro_bias).norm(), 1e-4);
  const Eigen::Vector3d g_V_true = T_V_W.linear() * Eigen::Vector3d(0, 0, -9.81);
  EXPECT_LT(std::acos(std::min(1.0, a->gravity_V.normalized().dot(g_V_true.normalized()))),
            0.2 * M_PI / 180.0);
  for (std::size_t i = 0; i < T_V_B.size(); ++i) {
    EXPECT_LT((a->v_V_B[i] - T_V_W.linear() * s.v_W_B_truth[60 + i]).norm(), 0.01) << i;
  }
}

}  // namespace
}  // namespace strata::odometry
