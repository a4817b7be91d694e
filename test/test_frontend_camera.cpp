// Visual front end, pieces without images: the distorted camera models, stereo extrinsics,
// triangulation, and the geometric outlier check against injected outliers.
#include <gtest/gtest.h>

#include <random>
#include <vector>

#include "strata/core/error.h"
#include "strata/odometry/frontend/camera.h"
#include "strata/odometry/frontend/geometric_check.h"
#include "strata/odometry/frontend/keyframe_policy.h"
#include "strata/odometry/frontend/stereo_matcher.h"

namespace strata::odometry {
namespace {

// EuRoC V1_01 cam0 as published in its sensor.yaml.
Camera eurocCam0() {
  Camera c;
  c.distortion = DistortionModel::kRadialTangential;
  c.coefficients = {-0.28340811, 0.07395907, 0.00019359, 1.76187114e-05};
  c.name = "cam0";
  return c;
}

TEST(FrontendCamera, RadTanAndEquidistantRoundTripOverTheImage) {
  Camera radtan = eurocCam0();
  Camera fisheye = radtan;
  fisheye.distortion = DistortionModel::kEquidistant;
  fisheye.coefficients = {-0.01, 0.02, -0.005, 0.001};
  for (const Camera& cam : {radtan, fisheye}) {
    double worst = 0.0;
    for (int v = 0; v < cam.height_px; v += 16) {
      for (int u = 0; u < cam.width_px; u += 16) {
        const Eigen::Vector2d uv(u, v);
        worst = std::max(worst, (cam.project(cam.undistort(uv)) - uv).norm());
      }
    }
    EXPECT_LT(worst, 1e-8);
  }
  // Distortion is real: a corner pixel moves by tens of pixels when undistorted.
  const Eigen::Vector2d corner(0, 0);
  const Eigen::Vector2d xy = radtan.undistort(corner);
  const Eigen::Vector2d pinhole(radtan.fx_px * xy.x() + radtan.cx_px,
                                radtan.fy_px * xy.y() + radtan.cy_px);
  EXPECT_GT((pinhole - corner).norm(), 30.0);
  // Known forward value: k1 term only at x = 0.1: x_d = 0.1 (1 + k1 0.01 + k2 1e-4) + tangential.
  Camera k1_only = radtan;
  k1_only.coefficients = {-0.2, 0.0, 0.0, 0.0};
  EXPECT_NEAR(k1_only.project({0.1, 0.0}).x(), k1_only.fx_px * 0.1 * (1 - 0.002) + k1_only.cx_px,
              1e-9);
}

TEST(FrontendCamera, StereoExtrinsicsFromBodyPosesAndBadCalibrationsNamed) {
  StereoCamera rig;
  rig.left = eurocCam0();
  rig.right = eurocCam0();
  rig.right.name = "cam1";
  const Eigen::Isometry3d T_B_C0 = Eigen::Translation3d(0.1, 0.2, 0.3) *
                                   Eigen::AngleAxisd(0.4, Eigen::Vector3d(1, 2, 3).normalized());
  const Eigen::Isometry3d T_C0_C1 =
      Eigen::Translation3d(0.11, 0.001, -0.002) * Eigen::AngleAxisd(0.01, Eigen::Vector3d::UnitY());
  rig.left.T_B_C = T_B_C0;
  rig.right.T_B_C = T_B_C0 * T_C0_C1;
  EXPECT_LT((rig.T_C0_C1().matrix() - T_C0_C1.matrix()).norm(), 1e-12);
  EXPECT_NEAR(rig.baseline_m(), T_C0_C1.translation().norm(), 1e-12);
  EXPECT_NO_THROW(rig.validate());
  // Epipolar constraint and triangulation of a point at 2.5 m.
  const Eigen::Vector3d p_C0(0.3, -0.2, 2.5);
  const Eigen::Vector3d p_C1 = T_C0_C1.inverse() * p_C0;
  const Eigen::Vector2d xl = p_C0.hnormalized(), xr = p_C1.hnormalized();
  EXPECT_NEAR(xr.homogeneous().dot(rig.essentialRightLeft() * xl.homogeneous()), 0.0, 1e-12);
  const auto depths = triangulateDepths(xl, xr, T_C0_C1.inverse());
  ASSERT_TRUE(depths);
  EXPECT_NEAR(depths->x(), 2.5, 1e-9);
  EXPECT_NEAR(depths->y(), p_C1.z(), 1e-9);

  // Gyro prediction: the body's rotation between two frames seen from the camera.
  const Eigen::Matrix3d R_W_B0 =
      Eigen::AngleAxisd(0.3, Eigen::Vector3d(1, 0, 1).normalized()).matrix();
  const Eigen::Matrix3d R_W_B1 =
      Eigen::AngleAxisd(0.5, Eigen::Vector3d(0, 1, 1).normalized()).matrix();
  const Eigen::Matrix3d R_C1_C0_expected =
      (R_W_B1 * T_B_C0.linear()).transpose() * R_W_B0 * T_B_C0.linear();
  EXPECT_LT((cameraRotation(R_W_B1.transpose() * R_W_B0, T_B_C0) - R_C1_C0_expected).norm(), 1e-12);

  rig.right.T_B_C = rig.left.T_B_C;
  EXPECT_THROW(
      {
        try {
          rig.validate();
        } catch (const InputError& e) {
          EXPECT_NE(std::string(e.what()).find("baseline"), std::string::npos) << e.what();
          throw;
        }
      },
      InputError);
  Camera bad = eurocCam0();
  bad.fx_px = 0.0;
  EXPECT_THROW(bad.validate(), InputError);
}

struct Correspondences {
  std::vector<Eigen::Vector2d> prev, cur;
  std::vector<bool> outlier;
};

// Random points 2..8 m ahead seen from two poses; a share of them displaced 4..30 px.
Correspondences makeCorrespondences(const Eigen::Isometry3d& T_cur_prev, double outlier_share,
                                    double focal_px, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> lateral(-1.0, 1.0), depth(2.0, 8.0), unit(0.0, 1.0);
  std::uniform_real_distribution<double> shift(4.0, 30.0), angle(0.0, 6.283185307);
  std::normal_distribution<double> noise(0.0, 0.2 / focal_px);
  Correspondences c;
  for (int i = 0; i < 200; ++i) {
    const double z = depth(rng);
    const Eigen::Vector3d p_prev(lateral(rng) * 0.6 * z, lateral(rng) * 0.4 * z, z);
    Eigen::Vector2d cur = (T_cur_prev * p_prev).hnormalized();
    const bool outlier = unit(rng) < outlier_share;
    if (outlier) {
      const double a = angle(rng);
      cur += shift(rng) / focal_px * Eigen::Vector2d(std::cos(a), std::sin(a));
    }
    c.prev.push_back(p_prev.hnormalized() + Eigen::Vector2d(noise(rng), noise(rng)));
    c.cur.push_back(cur + Eigen::Vector2d(noise(rng), noise(rng)));
    c.outlier.push_back(outlier);
  }
  return c;
}

void expectOutliersCaught(const Correspondences& c, const GeometricCheckResult& r) {
  int outliers = 0, caught = 0, inliers = 0, kept = 0;
  for (std::size_t i = 0; i < c.outlier.size(); ++i) {
    if (c.outlier[i]) {
      ++outliers;
      caught += r.inlier[i] == 0;
    } else {
      ++inliers;
      kept += r.inlier[i] == 1;
    }
  }
  ASSERT_GT(outliers, 10);
  EXPECT_GE(caught, 0.95 * outliers) << caught << " of " << outliers;
  EXPECT_GE(kept, 0.95 * inliers) << kept << " of " << inliers;
  EXPECT_EQ(r.rejected, static_cast<int>(std::count(r.inlier.begin(), r.inlier.end(), 0)));
}

TEST(FrontendGeometry, EssentialRansacCatchesInjectedOutliersWhileMoving) {
  const double focal = 460.0;
  const Eigen::Isometry3d T_cur_prev =
      Eigen::Translation3d(0.15, -0.02, 0.05) * Eigen::AngleAxisd(0.05, Eigen::Vector3d::UnitY());
  const Correspondences c = makeCorrespondences(T_cur_prev, 0.2, focal, 7);
  const GeometricCheckResult r = rejectOutliers(c.prev, c.cur, std::nullopt, focal, {});
  EXPECT_EQ(r.model, 'E');
  expectOutliersCaught(c, r);
}

TEST(FrontendGeometry, HomographyCatchesMovingPointsWhenTheCameraStandsStill) {
  // A still camera leaves the essential matrix undetermined; the small-parallax rule uses H
  // while it rejects under max_homography_reject_share (15 %) of the points: 10 % move here.
  const double focal = 460.0;
  const Correspondences c = makeCorrespondences(Eigen::Isometry3d::Identity(), 0.1, focal, 11);
  const GeometricCheckResult r = rejectOutliers(c.prev, c.cur, std::nullopt, focal, {});
  EXPECT_EQ(r.model, 'H');
  expectOutliersCaught(c, r);
  // Pure rotation with its prediction: parallax compensated to ~0, still 'H', still caught.
  const Eigen::Matrix3d R =
      Eigen::AngleAxisd(0.08, Eigen::Vector3d(0.2, 1, 0).normalized()).matrix();
  Eigen::Isometry3d T_rot = Eigen::Isometry3d::Identity();
  T_rot.linear() = R;
  const Correspondences cr = makeCorrespondences(T_rot, 0.1, focal, 13);
  const GeometricCheckResult rr = rejectOutliers(cr.prev, cr.cur, R, focal, {});
  EXPECT_LT(rr.median_parallax_px, 1.0);
  EXPECT_EQ(rr.model, 'H');
  expectOutliersCaught(cr, rr);
  // A third of the points moving is more than H may reject: E takes over (and is told so).
  const Correspondences many = makeCorrespondences(Eigen::Isometry3d::Identity(), 0.33, focal, 17);
  EXPECT_EQ(rejectOutliers(many.prev, many.cur, std::nullopt, focal, {}).model, 'E');
}

// ---------------------------------------------------------------------------------------------
// Keyframe policy

std::vector<FeatureObservation> grid(int n, double shift_px, double focal, int first_id = 0) {
  std::vector<FeatureObservation> features;
  for (int i = 0; i < n; ++i) {
    FeatureObservation f;
    f.track_id = static_cast<std::uint64_t>(first_id + i);
    f.xy_left_norm = Eigen::Vector2d(0.01 * (i % 10) - 0.05, 0.01 * (i / 10) - 0.05) +
                     Eigen::Vector2d(shift_px / focal, 0.0);
    features.push_back(f);
  }
  return features;
}

TEST(FrontendKeyframes, ParallaxTrackedShareIntervalAndLossEachMakeAKeyframe) {
  const double focal = 460.0;
  const std::int64_t ms = 1'000'000;
  double parallax = 0.0;
  KeyframePolicy policy(KeyframeConfig{});  // 10 px, 60 %, 0.5 s
  EXPECT_TRUE(policy.decide(0, grid(100, 0, focal), std::nullopt, focal, false, &parallax));
  EXPECT_FALSE(
      policy.decide(50 * ms, grid(100, 9.0, focal), std::nullopt, focal, false, &parallax));
  EXPECT_NEAR(parallax, 9.0, 1e-9);
  EXPECT_TRUE(
      policy.decide(100 * ms, grid(100, 10.5, focal), std::nullopt, focal, false, &parallax));
  // 55 of the keyframe's 100 tracks left (plus new ones): below 60 %.
  std::vector<FeatureObservation> some = grid(55, 10.5, focal);
  for (const FeatureObservation& f : grid(45, 0, focal, 1000)) some.push_back(f);
  EXPECT_TRUE(policy.decide(150 * ms, some, std::nullopt, focal, false, &parallax));
  EXPECT_FALSE(policy.decide(600 * ms, some, std::nullopt, focal, false, &parallax));
  EXPECT_TRUE(policy.decide(650 * ms, some, std::nullopt, focal, false, &parallax));  // 0.5 s
  EXPECT_TRUE(policy.decide(700 * ms, some, std::nullopt, focal, true, &parallax));   // lost

  // Turning on the spot with predictions: 20 px of flow, ~0 parallax, no keyframe.
  KeyframePolicy turning(KeyframeConfig{});
  std::vector<FeatureObservation> before = grid(100, 0, focal);
  EXPECT_TRUE(turning.decide(0, before, std::nullopt, focal, false, &parallax));
  const Eigen::Matrix3d R = Eigen::AngleAxisd(20.0 / focal, Eigen::Vector3d::UnitY()).matrix();
  for (FeatureObservation& f : before) {
    f.xy_left_norm = (R * f.xy_left_norm.homogeneous()).hnormalized();
  }
  EXPECT_FALSE(turning.decide(50 * ms, before, R, focal, false, &parallax));
  EXPECT_LT(parallax, 0.5);
}

}  // namespace
}  // namespace strata::odometry
