// Odometry fused with localisations (localize/pose_fusion.h) on synthetic motion with known
// truth: drifting odometry corrected, a wrong localisation neither initialises nor moves the
// pose, updates bounded by the correction's uncertainty, bad odometry refused.
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>

#include <cmath>
#include <random>

#include "strata/core/error.h"
#include "strata/localize/pose_fusion.h"

namespace strata::localize {
namespace {

Eigen::Isometry3d pose(double x, double y, double yaw) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  T.translation() = Eigen::Vector3d(x, y, 1.2);
  return T;
}

/// A walk around a 10 m x 6 m loop, 0.2 m per step, twice.
std::vector<Eigen::Isometry3d> truthLoop() {
  std::vector<Eigen::Isometry3d> out;
  const double perimeter = 32.0;
  for (double s = 0.0; s < 2.0 * perimeter; s += 0.2) {
    const double u = std::fmod(s, perimeter);
    double x, y, yaw;
    if (u < 10) x = u, y = 0, yaw = 0;
    else if (u < 16) x = 10, y = u - 10, yaw = M_PI / 2;
    else if (u < 26) x = 26 - u, y = 6, yaw = M_PI;
    else x = 0, y = 32 - u, yaw = -M_PI / 2;
    out.push_back(pose(x, y, yaw));
  }
  return out;
}

/// Odometry in its own frame (offset from the map) with a yaw and translation drift of about
/// 2 % of the distance.
std::vector<Eigen::Isometry3d> drifted(const std::vector<Eigen::Isometry3d>& truth,
                                       const Eigen::Isometry3d& T_O_W, std::uint32_t seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> n(0.0, 1.0);
  std::vector<Eigen::Isometry3d> out{T_O_W * truth[0]};
  for (std::size_t i = 1; i < truth.size(); ++i) {
    Eigen::Isometry3d step = Eigen::Isometry3d::Identity();
    step.translation() = Eigen::Vector3d(0.004 + 0.002 * n(rng), 0.002 * n(rng), 0.0);
    step.linear() = Eigen::AngleAxisd(0.002 + 0.001 * n(rng), Eigen::Vector3d::UnitZ()).toRotationMatrix();
    const Eigen::Isometry3d motion = truth[i - 1].inverse() * truth[i];
    out.push_back(out.back() * motion * step);
  }
  return out;
}

Localization localizationAt(const Eigen::Isometry3d& T_W_C, double sigma_m, std::mt19937& rng) {
  std::normal_distribution<double> n(0.0, sigma_m);
  Localization l;
  l.localized = true;
  l.T_W_C = T_W_C;
  l.T_W_C.translation() += Eigen::Vector3d(n(rng), n(rng), n(rng));
  l.covariance = Eigen::Matrix<double, 6, 6>::Identity() * sigma_m * sigma_m;
  return l;
}

double positionError(const FusedPose& f, const Eigen::Isometry3d& truth) {
  return (f.T_W_C.translation() - truth.translation()).norm();
}

TEST(PoseFusion, LocalisationsHoldDriftingOdometryToTheMap) {
  const std::vector<Eigen::Isometry3d> truth = truthLoop();
  const Eigen::Isometry3d T_O_W = pose(3.0, -2.0, 0.7);
  const std::vector<Eigen::Isometry3d> odometry = drifted(truth, T_O_W, 4);
  FusionConfig config;  // the localisations here are as good as they say: 1 cm
  config.min_localization_sigma_m = 0.01;
  PoseFusion fusion(config);
  std::mt19937 rng(9);
  double max_error = 0.0, odometry_error = 0.0;
  for (std::size_t i = 0; i < truth.size(); ++i) {
    FusedPose f = fusion.predict(0.2 * i, odometry[i]);
    if (i % 5 == 0) f = fusion.correct(localizationAt(truth[i], 0.01, rng));
    if (i > 10) {
      ASSERT_NE(f.status, FusionStatus::kUninitialised) << "frame " << i;
      max_error = std::max(max_error, positionError(f, truth[i]));
    }
    // What the odometry alone would say, placed by its first pose's truth.
    const Eigen::Isometry3d T_W_O = truth[0] * odometry[0].inverse();
    odometry_error = std::max(odometry_error, ((T_W_O * odometry[i]).translation() -
                                               truth[i].translation()).norm());
  }
  std::printf("fusion: largest error %.1f mm; odometry alone %.0f mm\n", 1e3 * max_error,
              1e3 * odometry_error);
  EXPECT_GT(odometry_error, 0.5);  // the drift is real
  // Between two localisations (1 m) this odometry drifts 4-6 cm; the bound leaves room for the
  // draw of the noise, which differs between compilers.
  EXPECT_LT(max_error, 0.08);
  EXPECT_EQ(fusion.rejected(), 0u);
}

TEST(PoseFusion, OneWrongLocalisationNeitherInitialisesNorMovesThePose) {
  const std::vector<Eigen::Isometry3d> truth = truthLoop();
  PoseFusion fusion;
  std::mt19937 rng(2);
  // Alone, a localisation 2 m off does not initialise: the next good one disagrees with it.
  fusion.predict(0.0, truth[0]);
  Eigen::Isometry3d wrong = truth[0];
  wrong.translation().x() += 2.0;
  EXPECT_EQ(fusion.correct(localizationAt(wrong, 0.01, rng)).status, FusionStatus::kUninitialised);
  fusion.predict(0.2, truth[1]);
  EXPECT_EQ(fusion.correct(localizationAt(truth[1], 0.01, rng)).status,
            FusionStatus::kUninitialised);
  fusion.predict(0.4, truth[2]);
  const FusedPose init = fusion.correct(localizationAt(truth[2], 0.01, rng));
  ASSERT_EQ(init.status, FusionStatus::kCorrected);
  EXPECT_LT(positionError(init, truth[2]), 0.05);
  for (std::size_t i = 3; i < 40; ++i) {
    fusion.predict(0.2 * i, truth[i]);
    fusion.correct(localizationAt(truth[i], 0.01, rng));
  }
  // Initialised: a wrong one is gated out, the pose does not move.
  fusion.predict(8.0, truth[40]);
  wrong = truth[40];
  wrong.translation().y() += 0.8;
  const std::size_t rejected = fusion.rejected();
  const FusedPose f = fusion.correct(localizationAt(wrong, 0.01, rng));
  EXPECT_EQ(fusion.rejected(), rejected + 1);
  EXPECT_EQ(f.status, FusionStatus::kTracking);
  EXPECT_EQ(f.jump_m, 0.0);
  EXPECT_LT(positionError(f, truth[40]), 0.05);
  EXPECT_NE(f.note.find("rejected"), std::string::npos) << f.note;
}

TEST(PoseFusion, AnUpdateMovesThePoseByNoMoreThanTheGateAllows) {
  const std::vector<Eigen::Isometry3d> truth = truthLoop();
  const std::vector<Eigen::Isometry3d> odometry = drifted(truth, Eigen::Isometry3d::Identity(), 7);
  FusionConfig config;
  PoseFusion fusion(config);
  std::mt19937 rng(5);
  for (std::size_t i = 0; i < truth.size(); ++i) {
    const FusedPose before = fusion.predict(0.2 * i, odometry[i]);
    if (i % 15 != 0) continue;
    const FusedPose after = fusion.correct(localizationAt(truth[i], 0.02, rng));
    if (before.status == FusionStatus::kUninitialised || after.status != FusionStatus::kCorrected)
      continue;
    // The step K * innovation is at most sqrt(gate) standard deviations of the prediction
    // (|P S^-1 v|^2 <= lambda_max(P) * v' S^-1 v with S = P + R).
    Eigen::SelfAdjointEigenSolver<Matrix6d> eigen(before.covariance);
    const double bound = std::sqrt(config.gate_chi2 * eigen.eigenvalues().maxCoeff()) + 1e-9;
    EXPECT_LE(after.jump_m, bound) << "frame " << i;
    EXPECT_NEAR((after.T_W_C.translation() - before.T_W_C.translation()).norm(), after.jump_m, 1e-9);
  }
}

TEST(PoseFusion, BadOdometryIsRefusedAndChangesNothing) {
  PoseFusion fusion;
  fusion.predict(1.0, pose(0, 0, 0));
  EXPECT_THROW(fusion.predict(0.5, pose(0.1, 0, 0)), InputError);  // time going backwards
  Eigen::Isometry3d nan = pose(0, 0, 0);
  nan.translation().x() = std::nan("");
  EXPECT_THROW(fusion.predict(2.0, nan), InputError);
  EXPECT_NO_THROW(fusion.predict(1.5, pose(0.1, 0, 0)));  // the last good time still holds
  FusionConfig bad;
  bad.gate_chi2 = -1.0;
  EXPECT_THROW(PoseFusion{bad}, InputError);
}

}  // namespace
}  // namespace strata::localize
