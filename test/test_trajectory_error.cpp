// Trajectory accuracy on trajectories with a known error: alignment recovers a known transform,
// ATE equals a known offset, RPE a known drift, and bad input is refused with a clear message.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "cli/eval_trajectory_command.h"
#include "strata/core/error.h"
#include "strata/trajectory/trajectory_error.h"

namespace strata::trajectory {
namespace {

namespace fs = std::filesystem;

Eigen::Isometry3d pose(const Eigen::Vector3d& t, double yaw_rad = 0.0) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = Eigen::AngleAxisd(yaw_rad, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  T.translation() = t;
  return T;
}

/// n poses on a circle of radius r in the z = 1 plane, 10 Hz, looking along the tangent.
std::vector<StampedPose> circle(std::size_t n, double radius_m) {
  std::vector<StampedPose> poses;
  for (std::size_t i = 0; i < n; ++i) {
    const double a = 2.0 * M_PI * static_cast<double>(i) / static_cast<double>(n);
    poses.push_back({0.1 * static_cast<double>(i),
                     pose({radius_m * std::cos(a), radius_m * std::sin(a), 1.0}, a + M_PI / 2)});
  }
  return poses;
}

std::vector<StampedPose> transformed(const std::vector<StampedPose>& in, const Eigen::Isometry3d& T,
                                     double scale) {
  std::vector<StampedPose> out = in;
  for (StampedPose& p : out) {
    Eigen::Isometry3d q = p.T_W_C;
    q.translation() *= scale;
    p.T_W_C = T * q;
  }
  return out;
}

const Eigen::Isometry3d kSomeTransform = [] {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  T.translation() = Eigen::Vector3d(4.0, -2.0, 0.5);
  return T;
}();

TEST(TrajectoryError, IdenticalTrajectoriesHaveNoError) {
  const auto truth = circle(64, 2.0);
  const TrajectoryError e = evaluateTrajectory(truth, truth, Alignment::kSE3);
  EXPECT_EQ(e.matched, 64u);
  EXPECT_NEAR(e.ate_rmse_m, 0.0, 1e-9);
  EXPECT_NEAR(e.rotation_rmse_deg, 0.0, 1e-6);
  EXPECT_NEAR(e.rpe_trans_percent, 0.0, 1e-7);
  EXPECT_GT(e.rpe_pairs, 40u);
  EXPECT_NEAR(e.path_length_m, 2.0 * 63 * 2.0 * std::sin(M_PI / 64), 1e-9);
}

TEST(TrajectoryError, Se3AlignmentRemovesARigidTransformAndRecoversIt) {
  const auto truth = circle(64, 2.0);
  const auto estimate = transformed(truth, kSomeTransform, 1.0);
  const TrajectoryError e = evaluateTrajectory(estimate, truth, Alignment::kSE3);
  EXPECT_NEAR(e.ate_rmse_m, 0.0, 1e-9);
  EXPECT_NEAR(e.rotation_rmse_deg, 0.0, 1e-6);
  EXPECT_TRUE(e.aligned.T_gt_est.isApprox(kSomeTransform.inverse(), 1e-9));
  EXPECT_NEAR(e.rpe_trans_percent, 0.0, 1e-7);  // RPE never depends on the world frame
  const TrajectoryError none = evaluateTrajectory(estimate, truth, Alignment::kNone);
  EXPECT_GT(none.ate_rmse_m, 1.0);
  EXPECT_NEAR(none.rpe_trans_percent, 0.0, 1e-7);
}

TEST(TrajectoryError, Sim3AlignmentRecoversTheScaleOfAMonocularEstimate) {
  const auto truth = circle(64, 2.0);
  const auto estimate = transformed(truth, kSomeTransform, 0.4);
  const TrajectoryError sim3 = evaluateTrajectory(estimate, truth, Alignment::kSim3);
  EXPECT_NEAR(sim3.scale, 1.0 / 0.4, 1e-9);
  EXPECT_NEAR(sim3.ate_rmse_m, 0.0, 1e-9);
  EXPECT_NEAR(sim3.rpe_trans_percent, 0.0, 1e-6);
  const TrajectoryError se3 = evaluateTrajectory(estimate, truth, Alignment::kSE3);
  EXPECT_NEAR(se3.scale, 1.0, 0.0);
  EXPECT_NEAR(se3.ate_rmse_m, 2.0 * 0.6, 1e-6);  // radius 0.8 m against 2 m, same centre
  // Each 1 m segment is 6 chords of the 64-gon; its error is 60 % of the chord across them.
  const double chord_ratio = std::sin(6 * M_PI / 64) / (6 * std::sin(M_PI / 64));
  EXPECT_NEAR(se3.rpe_trans_percent, 60.0 * chord_ratio, 1e-6);
}

TEST(TrajectoryError, AteOfAKnownPerpendicularOffsetIsThatOffset) {
  // Alternate poses 3 cm above and below the truth's plane: no rigid motion removes any of it.
  const auto truth = circle(64, 2.0);
  auto estimate = truth;
  for (std::size_t i = 0; i < estimate.size(); ++i) {
    estimate[i].T_W_C.translation().z() += (i % 2 == 0 ? 0.03 : -0.03);
  }
  for (Alignment a : {Alignment::kNone, Alignment::kSE3}) {
    const TrajectoryError e = evaluateTrajectory(estimate, truth, a);
    EXPECT_NEAR(e.ate_rmse_m, 0.03, 1e-9) << alignmentName(a);
    EXPECT_NEAR(e.ate_mean_m, 0.03, 1e-9);
    EXPECT_NEAR(e.ate_median_m, 0.03, 1e-9);
    EXPECT_NEAR(e.ate_max_m, 0.03, 1e-9);
  }
}

/// A straight walk along x at 0.25 m steps, 20 m.
std::vector<StampedPose> line() {
  std::vector<StampedPose> poses;
  for (int i = 0; i <= 80; ++i) poses.push_back({0.1 * i, pose({0.25 * i, 0.0, 0.0})});
  return poses;
}

TEST(TrajectoryError, RpeOfAScaleDriftIsThatDriftInPercent) {
  const auto truth = line();
  const auto estimate = transformed(truth, Eigen::Isometry3d::Identity(), 1.02);
  const TrajectoryError e = evaluateTrajectory(estimate, truth, Alignment::kFirstPose);
  EXPECT_EQ(e.rpe_pairs, 77u);  // starts 0..76 have a pose 1 m further
  EXPECT_NEAR(e.rpe_trans_percent, 2.0, 1e-9);
  EXPECT_NEAR(e.rpe_rot_deg_per_m, 0.0, 1e-9);
  EXPECT_NEAR(e.ate_max_m, 0.02 * 20.0, 1e-9);  // drift from the first pose grows to 40 cm
}

TEST(TrajectoryError, RpeOfAHeadingDriftIsThatDriftPerMetre) {
  const auto truth = line();
  auto estimate = truth;
  const double drift_deg_per_m = 0.5;
  for (StampedPose& p : estimate) {
    const double x_m = p.T_W_C.translation().x();
    p.T_W_C.linear() =
        Eigen::AngleAxisd(drift_deg_per_m * x_m * M_PI / 180.0, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  }
  const TrajectoryError e = evaluateTrajectory(estimate, truth, Alignment::kNone);
  EXPECT_NEAR(e.rpe_rot_deg_per_m, drift_deg_per_m, 1e-9);
  EXPECT_NEAR(e.ate_rmse_m, 0.0, 1e-12);  // positions are exact; only headings drift
}

TEST(TrajectoryError, AStraightPathTakesItsRotationFromTheOrientations) {
  // Positions on a line leave the rotation about it free; orientations pin it.
  const auto truth = line();
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = Eigen::AngleAxisd(0.5, Eigen::Vector3d::UnitX()).toRotationMatrix();
  T.translation() = Eigen::Vector3d(0.3, -1.0, 2.0);
  const auto estimate = transformed(truth, T, 1.0);
  const TrajectoryError e = evaluateTrajectory(estimate, truth, Alignment::kSE3);
  EXPECT_TRUE(e.aligned.rotation_from_orientations);
  EXPECT_TRUE(e.aligned.T_gt_est.isApprox(T.inverse(), 1e-9));
  EXPECT_NEAR(e.ate_rmse_m, 0.0, 1e-9);
  EXPECT_NEAR(e.rotation_rmse_deg, 0.0, 1e-6);
  const TrajectoryError sim3 = evaluateTrajectory(transformed(truth, T, 2.0), truth, Alignment::kSim3);
  EXPECT_NEAR(sim3.scale, 0.5, 1e-9);
  EXPECT_NEAR(sim3.rotation_rmse_deg, 0.0, 1e-6);
  EXPECT_FALSE(evaluateTrajectory(circle(64, 2.0), circle(64, 2.0), Alignment::kSE3)
                   .aligned.rotation_from_orientations);
}

TEST(TrajectoryError, FirstPoseAlignmentMeasuresDriftFromTheStart) {
  const auto truth = line();
  auto estimate = transformed(truth, kSomeTransform, 1.0);
  estimate.back().T_W_C.translation() += kSomeTransform.linear() * Eigen::Vector3d(0, 0.05, 0);
  const TrajectoryError e = evaluateTrajectory(estimate, truth, Alignment::kFirstPose);
  EXPECT_NEAR(e.ate_max_m, 0.05, 1e-9);
  EXPECT_NEAR(e.position_errors_m.front(), 0.0, 1e-12);
}

TEST(TrajectoryError, AssociatesByNearestTimestampWithinTheTolerance) {
  const auto truth = line();
  std::vector<StampedPose> estimate;
  for (std::size_t i = 0; i < truth.size(); i += 2) {
    estimate.push_back({truth[i].timestamp_s + 0.004, truth[i].T_W_C});
  }
  estimate.push_back({100.0, pose({0, 0, 0})});  // no truth near: left out
  const TrajectoryError e = evaluateTrajectory(estimate, truth, Alignment::kNone, 0.01);
  EXPECT_EQ(e.estimated, 42u);
  EXPECT_EQ(e.matched, 41u);
  EXPECT_NEAR(e.ate_rmse_m, 0.0, 1e-12);
  EXPECT_THROW(evaluateTrajectory(estimate, truth, Alignment::kNone, 0.001), InputError);
}

TEST(TrajectoryError, RefusesBadInputWithAClearMessage) {
  const auto truth = line();
  auto nan_estimate = truth;
  nan_estimate[3].T_W_C.translation().x() = NAN;
  try {
    evaluateTrajectory(nan_estimate, truth, Alignment::kSE3);
    FAIL() << "a NaN pose was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("not finite"), std::string::npos) << e.what();
  }
  std::vector<StampedPose> still(10, StampedPose{0.0, pose({1, 2, 3})});
  for (std::size_t i = 0; i < still.size(); ++i) still[i].timestamp_s = 0.1 * i;
  try {
    evaluateTrajectory(still, truth, Alignment::kSim3);
    FAIL() << "Sim(3) of a trajectory with no extent was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("scale is unobservable"), std::string::npos) << e.what();
  }
  // A still estimate has an SE(3) error all the same (standstill checks use it).
  EXPECT_NO_THROW(evaluateTrajectory(still, truth, Alignment::kSE3));
  EXPECT_THROW(parseAlignment("umeyama"), InputError);
  EXPECT_THROW(evaluateTrajectory({}, truth, Alignment::kSE3), InputError);
}

TEST(TrajectoryError, JsonWritesNullForAMissingRpe) {
  const auto truth = circle(8, 0.05);  // 30 cm of path: no 1 m segment
  const TrajectoryError e = evaluateTrajectory(truth, truth, Alignment::kSE3);
  EXPECT_EQ(e.rpe_pairs, 0u);
  const std::string json = trajectoryErrorJson(e);
  EXPECT_NE(json.find("\"rpe_trans_percent\": null"), std::string::npos) << json;
  EXPECT_NE(json.find("\"matched\": 8"), std::string::npos) << json;
}

void writeTum(const fs::path& path, const std::vector<StampedPose>& poses) {
  std::ofstream out(path);
  out << "# timestamp tx ty tz qx qy qz qw\n";
  for (const StampedPose& p : poses) out << p.timestamp_s << " " << tum::poseToTum(p.T_W_C) << "\n";
}

TEST(EvalTrajectoryCommand, WritesJsonAndPlotAndRefusesAMissingFile) {
  const fs::path dir = fs::temp_directory_path() / ("strata_traj_" + std::to_string(getpid()));
  fs::create_directories(dir);
  const auto truth = circle(64, 2.0);
  writeTum(dir / "gt.txt", truth);
  writeTum(dir / "est.txt", transformed(truth, kSomeTransform, 1.0));
  apps::EvalTrajectoryOptions o;
  o.estimate_path = (dir / "est.txt").string();
  o.truth_path = (dir / "gt.txt").string();
  o.json_path = (dir / "ate.json").string();
  o.plot_path = (dir / "ate.png").string();
  ASSERT_EQ(apps::runEvalTrajectory(o), 0);
  std::ifstream json(o.json_path);
  const std::string text((std::istreambuf_iterator<char>(json)), std::istreambuf_iterator<char>());
  EXPECT_NE(text.find("\"ate_rmse_m\": "), std::string::npos) << text;
  EXPECT_GT(fs::file_size(o.plot_path), 1000u);
  o.truth_path = (dir / "absent.txt").string();
  EXPECT_EQ(apps::runEvalTrajectory(o), 2);
  o.truth_path = (dir / "gt.txt").string();
  o.alignment = "sim4";
  EXPECT_EQ(apps::runEvalTrajectory(o), 2);
  fs::remove_all(dir);
}

}  // namespace
}  // namespace strata::trajectory
