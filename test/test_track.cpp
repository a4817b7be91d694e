// RGB-D tracking: the device normal equations against the C++ reference, poses recovered on the
// simulated room (a known offset, a short sequence against the simulator's exact truth), and
// lost frames refused without touching the map.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

#include "cli/fuse_command.h"
#include "fusion_fixture.h"
#include "strata/integrate/normal_estimation.h"
#include "strata/io/tum_format.h"
#include "strata/mapper/mapper.h"
#include "strata/sim/analytic_dataset.h"
#include "strata/sim/default_scene.h"
#include "strata/sim/session/sim_session.h"
#include "strata/sim/world/world_paths.h"
#include "strata/track/depth_filter.h"
#include "strata/track/gauss_newton.h"
#include "strata/track/live_pyramid.h"
#include "strata/track/normal_equations.h"
#include "strata/track/rgbd_tracker.h"

namespace strata {
namespace {

CameraIntrinsics smallCamera() {
  CameraIntrinsics in;
  in.width_px = 320;
  in.height_px = 240;
  in.fx_px = 262.5f;
  in.fy_px = 262.5f;
  in.cx_px = 159.5f;
  in.cy_px = 119.5f;
  return in;
}

sim::AnalyticDataset roomDataset(std::vector<Eigen::Isometry3d> poses) {
  sim::AnalyticDatasetConfig config;
  config.intrinsics = smallCamera();
  config.render_color = false;
  return sim::AnalyticDataset(sim::makeDefaultScene(), std::move(poses), config);
}

Eigen::Isometry3d perturbed(const Eigen::Isometry3d& T, const Eigen::Vector3d& t_m,
                            const Eigen::Vector3d& axis, double angle_deg) {
  Eigen::Isometry3d delta = Eigen::Isometry3d::Identity();
  delta.linear() = Eigen::AngleAxisd(angle_deg * M_PI / 180.0, axis.normalized()).matrix();
  delta.translation() = t_m;
  return T * delta;
}

double translationError(const Eigen::Isometry3d& a, const Eigen::Isometry3d& b) {
  return (a.translation() - b.translation()).norm();
}

TEST(TrackPyramid, HalfDepthAveragesOnlyTheNearSurface) {
  MapConfig map;
  DepthImage depth(4, 2, 0.0f);
  depth.at(0, 0) = 1.00f;
  depth.at(1, 0) = 1.02f;
  depth.at(0, 1) = 3.00f;  // background behind an edge: must not be mixed in
  depth.at(1, 1) = 0.0f;   // invalid
  depth.at(2, 0) = 0.0f;   // a block with no valid depth
  const DepthImage half = halfDepth(depth, map, 0.05f);
  ASSERT_EQ(half.width_px, 2);
  ASSERT_EQ(half.height_px, 1);
  EXPECT_NEAR(half.at(0, 0), 1.01f, 1e-6f);
  EXPECT_EQ(half.at(1, 0), 0.0f);
  const CameraIntrinsics coarse = halfIntrinsics(smallCamera());
  EXPECT_FLOAT_EQ(coarse.cx_px, 79.5f);
  EXPECT_FLOAT_EQ(coarse.fx_px, 131.25f);
}

/// Mean angle (degrees) between the depth normals of `depth` and the plane normal n_C, over the
/// pixels with a normal.
double meanNormalErrorDeg(const DepthImage& depth, const CameraIntrinsics& intrinsics,
                          const Eigen::Vector3f& n_C) {
  const FrameCamera camera = FrameCamera::from(intrinsics, Eigen::Isometry3d::Identity());
  double sum = 0.0;
  int count = 0;
  for (const Eigen::Vector4f& n : estimateNormalsReference(depth, camera, MapConfig{})) {
    if (n.w() < 0.5f) continue;
    sum += std::acos(std::min(1.0f, std::abs(n.head<3>().dot(n_C)))) * 180.0 / M_PI;
    ++count;
  }
  return sum / count;
}

TEST(TrackDepthFilter, SmoothsNoiseKeepsEdgesAndHoles) {
  // A wall 3 m away tilted 30° about the vertical axis, with a Kinect-like noise of 1.5 cm (about
  // three pixel footprints at 640x480); the right third is a step 20 cm nearer; a hole.
  CameraIntrinsics in;
  in.width_px = 160;
  in.height_px = 120;
  in.fx_px = in.fy_px = 525.0f;  // the footprint of a 640x480 Kinect pixel
  in.cx_px = 79.5f;
  in.cy_px = 59.5f;
  const Eigen::Vector3f n_C(std::sin(0.5236f), 0.0f, -std::cos(0.5236f));
  std::mt19937 rng(3);
  std::normal_distribution<float> noise(0.0f, 0.015f);
  DepthImage clean(in.width_px, in.height_px);
  DepthImage noisy(in.width_px, in.height_px);
  for (int v = 0; v < in.height_px; ++v) {
    for (int u = 0; u < in.width_px; ++u) {
      // On the plane n_C · p = -3: p = d · ray, so d = -3 / (n_C · ray).
      const Eigen::Vector3f ray((u - in.cx_px) / in.fx_px, (v - in.cy_px) / in.fy_px, 1.0f);
      const float d = -3.0f / n_C.dot(ray) - (u >= 2 * in.width_px / 3 ? 0.2f : 0.0f);
      clean.at(u, v) = d;
      noisy.at(u, v) = d + noise(rng);
    }
  }
  noisy.at(40, 40) = 0.0f;
  const MapConfig map;
  const DepthImage smoothed = bilateralFilterDepth(noisy, map, 2.0f, 0.02f);
  // Raw normals are off by more than the 30° normal gate on average; smoothed ones by under half.
  const double raw_error = meanNormalErrorDeg(noisy, in, n_C);
  const double smoothed_error = meanNormalErrorDeg(smoothed, in, n_C);
  std::printf("normal error: raw %.1f deg, smoothed %.1f deg\n", raw_error, smoothed_error);
  EXPECT_GT(raw_error, 30.0);
  EXPECT_LT(smoothed_error, 15.0);
  // The step stays a step (no depth between the two sides), the hole stays a hole.
  EXPECT_EQ(smoothed.at(40, 40), 0.0f);
  const int edge = 2 * in.width_px / 3;
  for (int v = 10; v < in.height_px - 10; ++v) {
    EXPECT_NEAR(smoothed.at(edge - 1, v), clean.at(edge - 1, v), 0.06f) << v;
    EXPECT_NEAR(smoothed.at(edge, v), clean.at(edge, v), 0.06f) << v;
  }
  // Off: the depth unchanged.
  EXPECT_EQ(bilateralFilterDepth(noisy, map, 0.0f, 0.02f).depth_m, noisy.depth_m);
}

TEST(TrackNormalEquations, DeviceMatchesReferenceAndVanishesAtTheTruth) {
  const Eigen::Isometry3d T0 = sim::makeDefaultTrajectory(10)[0];
  const Eigen::Isometry3d T1 = perturbed(T0, {0.02, -0.01, 0.015}, {1, 2, 0.5}, 1.5);
  const sim::AnalyticDataset dataset = roomDataset({T0, T1});
  MapperConfig config;
  Mapper mapper(config, test::sharedContext());
  mapper.integrate(dataset.load(0), dataset.intrinsics());
  const RaycastImage model = mapper.render(dataset.intrinsics(), T0);
  const ModelView model_view{dataset.intrinsics(), T0, &model.depth.depth_m, &model.normal_W,
                             &model.hit};
  const RgbdFrame live = dataset.load(1);
  const std::vector<LiveLevel> pyramid =
      buildLivePyramid(live.depth, dataset.intrinsics(), config.map, 3, 0.05f);
  std::vector<LiveView> views;
  for (const LiveLevel& l : pyramid) {
    views.push_back({l.intrinsics.width_px, l.intrinsics.height_px, &l.vertex_C, &l.normal_C});
  }
  NormalEquationsKernel kernel(test::sharedContext());
  kernel.setLive(views);
  kernel.setModel(model_view);
  const AssociationGates gates;
  for (const Eigen::Isometry3d& at : {T0, T1}) {
    for (int level = 0; level < 3; ++level) {
      const NormalEquations device = kernel.run(level, at, gates);
      const NormalEquations reference =
          normalEquationsReference(views[static_cast<std::size_t>(level)], model_view, at, gates);
      ASSERT_GT(reference.inliers, 100u) << "level " << level;
      // A pixel on a gate's edge may fall either way under float rounding.
      EXPECT_LE(std::abs(static_cast<double>(device.inliers) - reference.inliers),
                2.0 + 1e-3 * reference.inliers)
          << "level " << level;
      double scale = 0.0;
      for (double v : reference.JtJ) scale = std::max(scale, std::abs(v));
      double worst = 0.0;
      for (std::size_t k = 0; k < 21; ++k) {
        EXPECT_NEAR(device.JtJ[k], reference.JtJ[k], 1e-5 * scale) << "JtJ " << k;
        worst = std::max(worst, std::abs(device.JtJ[k] - reference.JtJ[k]) / scale);
      }
      std::printf("level %d: inliers %u vs %u, largest JtJ difference %.1e of the largest entry\n",
                  level, device.inliers, reference.inliers, worst);
      double r_scale = 1e-6;
      for (double v : reference.Jtr) r_scale = std::max(r_scale, std::abs(v));
      for (std::size_t k = 0; k < 6; ++k) {
        EXPECT_NEAR(device.Jtr[k], reference.Jtr[k], 1e-5 * r_scale) << "Jtr " << k;
      }
      EXPECT_NEAR(device.residual_sq, reference.residual_sq, 1e-5 * reference.residual_sq + 1e-12);
    }
  }
  // At the true pose the live points lie on the model: residuals within the map's resolution,
  // nearly every valid live pixel an inlier.
  const NormalEquations at_truth = kernel.run(0, T1, gates);
  EXPECT_LT(std::sqrt(at_truth.residual_sq / at_truth.inliers), 0.004);
  EXPECT_GT(at_truth.inliers, 0.8 * pyramid[0].valid);
  const NormalEquations off = kernel.run(0, T0, gates);
  EXPECT_GT(off.residual_sq / off.inliers, 4.0 * at_truth.residual_sq / at_truth.inliers);
}

TEST(TrackRgbd, RecoversAKnownOffset) {
  const Eigen::Isometry3d T0 = sim::makeDefaultTrajectory(10)[0];
  const Eigen::Isometry3d T1 = perturbed(T0, {0.04, 0.02, -0.03}, {0.3, 1, 0.2}, 3.0);
  const sim::AnalyticDataset dataset = roomDataset({T0, T1});
  Mapper mapper(MapperConfig{}, test::sharedContext());
  mapper.integrate(dataset.load(0), dataset.intrinsics());
  const TrackResult result = mapper.track(dataset.load(1), dataset.intrinsics(), T0);
  ASSERT_TRUE(result.ok()) << result.reason;
  EXPECT_LT(translationError(result.T_W_C, T1), 0.003);
  EXPECT_LT(rotationAngleDeg(result.T_W_C.inverse() * T1), 0.15);
  EXPECT_GT(result.inlier_fraction, 0.6);  // the moved view sees some unmapped surface
  EXPECT_LT(result.rms_m, 0.005);
  EXPECT_GT(result.iterations, 3);
}

TEST(TrackRgbd, ShortRoomSequenceWithinACentimetre) {
  const std::vector<Eigen::Isometry3d> truth = sim::makeDefaultTrajectory(30);
  const sim::AnalyticDataset dataset = roomDataset(truth);
  Mapper mapper(MapperConfig{}, test::sharedContext());
  double sum_sq = 0.0;
  double worst = 0.0;
  for (std::size_t i = 0; i < truth.size(); ++i) {
    RgbdFrame frame = dataset.load(i);
    // Only the first pose is given (it defines the world); the rest must come from tracking.
    if (i > 0) frame.T_W_C = Eigen::Isometry3d::Identity();
    const TrackedFrame tracked = mapper.trackAndIntegrate(frame, dataset.intrinsics());
    ASSERT_TRUE(tracked.fused) << "frame " << i << ": " << tracked.track.reason;
    const double e = translationError(tracked.track.T_W_C, truth[i]);
    sum_sq += e * e;
    worst = std::max(worst, e);
  }
  const double rmse = std::sqrt(sum_sq / truth.size());
  std::printf("room sequence: translation RMSE %.2f mm, worst %.2f mm\n", rmse * 1e3, worst * 1e3);
  EXPECT_LE(rmse, 0.01) << "worst " << worst;
  EXPECT_EQ(mapper.framesIntegrated(), truth.size());
}

TEST(TrackRgbd, NoisySimulatedRoomSession) {
  // The shipped room through the simulator's noisy camera (640x480, 15 Hz as `strata sim --rate
  // 15`): walls 3-5 m away, where the depth noise spans several pixel footprints. Tracking must
  // hold from the second frame on, whose map is the first frame alone.
  const auto world = std::make_shared<const sim::World>(sim::World::load(sim::findWorld("room")));
  sim::SimSessionConfig session_config;
  session_config.frame_rate_hz = 15.0;
  const sim::SimSessionDataset session(world, 0, session_config);
  Mapper mapper(MapperConfig{}, test::sharedContext());
  for (std::size_t i = 0; i < 4; ++i) {
    RgbdFrame frame = session.load(i);
    if (i > 0) frame.T_W_C = Eigen::Isometry3d::Identity();
    const TrackedFrame tracked = mapper.trackAndIntegrate(frame, session.intrinsics());
    ASSERT_TRUE(tracked.fused) << "frame " << i << ": " << tracked.track.reason;
    const double e = translationError(tracked.track.T_W_C, session.truePoses()[i]);
    std::printf("room frame %zu: inlier fraction %.3f, error %.2f mm\n", i,
                tracked.track.inlier_fraction, e * 1e3);
    // NOTE: geometry alone (TrackConfig::color_weight 0) was 3.4, 2.1 and 2.1 mm here; the
    // photometric term, which real data needs (docs/track.md), costs this simulated room about
    // 6 mm a frame (7.9, 9.7, 9.0 mm), cause not found yet.
    EXPECT_LT(e, 0.015);
    if (i > 0) {
      EXPECT_GT(tracked.track.inlier_fraction, 0.35);
    }
  }
}

TEST(TrackRgbd, BadFramesAreLostAndNotFused) {
  const std::vector<Eigen::Isometry3d> arc = sim::makeDefaultTrajectory(10);
  // A frame from elsewhere: the camera moved 1.5 m and turned away, the guess still at the map.
  const Eigen::Isometry3d elsewhere = perturbed(arc[0], {1.5, 0.0, 0.8}, {0, 1, 0}, 70.0);
  const sim::AnalyticDataset dataset = roomDataset({arc[0], elsewhere});
  Mapper mapper(MapperConfig{}, test::sharedContext());
  ASSERT_TRUE(mapper.trackAndIntegrate(dataset.load(0), dataset.intrinsics()).fused);
  const std::uint32_t blocks = mapper.blockCount();
  const TsdfMap before = mapper.download();

  RgbdFrame blank = dataset.load(0);
  std::fill(blank.depth.depth_m.begin(), blank.depth.depth_m.end(), 0.0f);
  RgbdFrame garbage = dataset.load(0);
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> depth(0.3f, 4.5f);
  for (float& d : garbage.depth.depth_m) d = depth(rng);
  // A flat wall 1.2 m ahead that the map does not hold: smooth, valid normals everywhere.
  RgbdFrame wall = dataset.load(0);
  std::fill(wall.depth.depth_m.begin(), wall.depth.depth_m.end(), 1.2f);
  for (const RgbdFrame& bad : {blank, garbage, wall, dataset.load(1)}) {
    const TrackedFrame tracked = mapper.trackAndIntegrate(bad, dataset.intrinsics());
    EXPECT_FALSE(tracked.fused);
    EXPECT_FALSE(tracked.track.ok());
    EXPECT_FALSE(tracked.track.reason.empty());
    std::printf("lost: %s\n", tracked.track.reason.c_str());
  }
  EXPECT_EQ(mapper.framesIntegrated(), 1u);
  EXPECT_EQ(mapper.blockCount(), blocks);
  const TsdfMap after = mapper.download();
  for (const auto& [index, block] : before.blocks()) {
    const auto* other = after.findBlock(index);
    ASSERT_NE(other, nullptr);
    for (std::size_t v = 0; v < block.size(); ++v) {
      ASSERT_EQ(block[v].weight, (*other)[v].weight);
      ASSERT_EQ(block[v].tsdf_m, (*other)[v].tsdf_m);
    }
  }
  // The tracker recovers from the last good pose: the first frame again is tracked ok.
  const TrackedFrame again = mapper.trackAndIntegrate(dataset.load(0), dataset.intrinsics());
  EXPECT_TRUE(again.fused) << again.track.reason;
  EXPECT_LT(translationError(again.track.T_W_C, arc[0]), 0.003);
}

// Point-to-plane rows [n, p x n] of points on the plane z = 1 (normal +z): tz, rx and ry are
// constrained, tx, ty and rz are not. A residual that rounding leaves in those directions must
// not move the pose when the solve is told the conditioning floor.
TEST(TrackGaussNewton, IllConditionedDirectionsGetNoStep) {
  NormalEquations sums;
  const Eigen::Vector3d n(0, 0, 1);
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Vector6d Jtr = Vector6d::Zero();
  Matrix6d H = Matrix6d::Zero();
  for (int k = 0; k < 500; ++k) {
    const Eigen::Vector3d p(u(rng), u(rng), 1.0);
    Vector6d J;
    J << n, p.cross(n);
    const double r = 0.002 + 1e-9 * u(rng);  // a 2 mm offset along the normal, plus noise
    H += J * J.transpose();
    Jtr += J * r;
  }
  Jtr[0] += 1e-7;  // rounding in an unconstrained direction (in-plane x)
  int k = 0;
  for (int i = 0; i < 6; ++i) {
    for (int j = i; j < 6; ++j) sums.JtJ[static_cast<std::size_t>(k++)] = H(i, j);
    sums.Jtr[static_cast<std::size_t>(i)] = Jtr[i];
  }
  sums.inliers = 500;
  const GaussNewtonStep truncated = solveGaussNewton(sums, 1e-4);
  ASSERT_TRUE(truncated.solved);
  EXPECT_EQ(truncated.unconstrained_directions, 3);
  EXPECT_NEAR(truncated.xi[2], -0.002, 1e-6);  // the constrained offset is removed
  EXPECT_LT(std::abs(truncated.xi[0]) + std::abs(truncated.xi[1]) + std::abs(truncated.xi[5]),
            1e-9);
  EXPECT_LT(truncated.min_eigenvalue, 1e-12);
  const GaussNewtonStep full = solveGaussNewton(sums);  // without the floor: no solution
  EXPECT_FALSE(full.solved && full.xi.head<2>().norm() < 1e-3);
}

TEST(TrackGaussNewton, StatedCovarianceMatchesTheSpreadOfTheEstimate) {
  // A linear least-squares problem with known noise: the spread of the solved ξ over many noise
  // draws is the covariance poseCovariance states from one draw's sums.
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::normal_distribution<double> noise(0.0, 0.003);  // 3 mm
  std::vector<Vector6d> rows;
  for (int k = 0; k < 400; ++k) {
    const Eigen::Vector3d p(u(rng), u(rng), 2.0 + 0.5 * u(rng));
    const Eigen::Vector3d n = Eigen::Vector3d(0.3 * u(rng), 0.3 * u(rng), 1.0).normalized();
    Vector6d J;
    J << n, p.cross(n);
    rows.push_back(J);
  }
  const int draws = 400;
  std::vector<Vector6d> estimates;
  Matrix6d stated_sum = Matrix6d::Zero();
  for (int d = 0; d < draws; ++d) {
    NormalEquations sums;
    Matrix6d H = Matrix6d::Zero();
    Vector6d Jtr = Vector6d::Zero();
    for (const Vector6d& J : rows) {
      const double r = noise(rng);  // the residual at ξ = 0; the truth is ξ = 0
      H += J * J.transpose();
      Jtr += J * r;
      sums.residual_sq += r * r;
    }
    int k = 0;
    for (int i = 0; i < 6; ++i) {
      for (int j = i; j < 6; ++j) sums.JtJ[static_cast<std::size_t>(k++)] = H(i, j);
      sums.Jtr[static_cast<std::size_t>(i)] = Jtr[i];
    }
    sums.inliers = static_cast<std::uint32_t>(rows.size());
    const GaussNewtonStep step = solveGaussNewton(sums);
    ASSERT_TRUE(step.solved);
    estimates.push_back(step.xi);
    // residual_sq at ξ = 0 overstates the minimum's by the fitted part (6 of 400 degrees of
    // freedom): well within the bound below.
    stated_sum += poseCovariance(sums, static_cast<double>(rows.size()));
  }
  Matrix6d empirical = Matrix6d::Zero();
  for (const Vector6d& xi : estimates) empirical += xi * xi.transpose();
  empirical /= draws;
  const Matrix6d stated = stated_sum / draws;
  for (int i = 0; i < 6; ++i) {
    // 400 draws: the sample variance is within ~15 % of the true one (3 sigma ≈ 21 %).
    EXPECT_NEAR(empirical(i, i) / stated(i, i), 1.0, 0.25) << "direction " << i;
  }
  NormalEquations singular;  // one row only: nothing is constrained
  singular.inliers = 1;
  EXPECT_FALSE(poseCovariance(singular, 1.0).allFinite());
}

TEST(TrackRgbd, AFloorAloneIsIllConditioned) {
  // Looking straight down at the bare floor: a plane leaves in-plane translation and the
  // rotation about its normal unconstrained.
  Eigen::Isometry3d down = Eigen::Isometry3d::Identity();
  down.linear() << 1, 0, 0, 0, -1, 0, 0, 0, -1;  // camera z = world -z
  down.translation() = Eigen::Vector3d(1.5, -1.5, 1.0);
  const sim::AnalyticDataset dataset = roomDataset({down});
  MapperConfig config;
  config.track.color_weight = 0.0;  // geometry alone (the floor's colour is another matter)
  Mapper mapper(config, test::sharedContext());
  mapper.integrate(dataset.load(0), dataset.intrinsics());
  const Eigen::Isometry3d guess = perturbed(down, {0.02, 0.01, 0.0}, {0, 0, 1}, 1.0);
  const TrackResult result = mapper.track(dataset.load(0), dataset.intrinsics(), guess);
  std::printf("floor: %s (smallest eigenvalue %.2e)\n", result.reason.c_str(),
              result.min_eigenvalue);
  EXPECT_FALSE(result.ok());
  EXPECT_NE(result.reason.find("ill-conditioned"), std::string::npos) << result.reason;
}

/// A flat wall 1 m in front of the camera painted with a 0.2 m sinusoidal pattern, seen from
/// `dx` metres to the side (camera x): depth and colour.
RgbdFrame texturedWall(const CameraIntrinsics& in, double dx) {
  RgbdFrame frame;
  frame.depth = DepthImage(in.width_px, in.height_px, 1.0f);
  frame.color = ColorImage(in.width_px, in.height_px);
  for (int v = 0; v < in.height_px; ++v) {
    for (int u = 0; u < in.width_px; ++u) {
      const double x = (u - in.cx_px) / in.fx_px + dx, y = (v - in.cy_px) / in.fy_px;
      const double value = 128.0 + 100.0 * std::sin(2 * M_PI * x / 0.2) * std::cos(2 * M_PI * y / 0.2);
      std::uint8_t* p = &frame.color.rgb[(static_cast<std::size_t>(v) * in.width_px + u) * 3];
      p[0] = p[1] = p[2] = static_cast<std::uint8_t>(std::lround(value));
    }
  }
  frame.T_W_C.translation().x() = dx;
  return frame;
}

TEST(TrackRgbd, ColourConstrainsWhatAPlaneLeavesLoose) {
  // A plane leaves its in-plane translation to the texture: with the photometric term the
  // sideways offset is recovered; geometry alone calls the frame ill-conditioned.
  const CameraIntrinsics in = smallCamera();
  MapperConfig config;
  config.map.voxel_size_m = 0.01f;
  Mapper mapper(config, test::sharedContext());
  for (int i = 0; i < 3; ++i) mapper.integrate(texturedWall(in, 0.0), in);
  const RgbdFrame moved = texturedWall(in, 0.02);
  const TrackResult with_colour = mapper.track(moved, in, Eigen::Isometry3d::Identity());
  ASSERT_TRUE(with_colour.ok()) << with_colour.reason;
  EXPECT_NEAR(with_colour.T_W_C.translation().x(), 0.02, 0.003);
  // NOTE: the depth is pulled 3.6 mm off the plane (measured): the strong pattern's term trades
  // against the point-to-plane one along z; the sideways step, which only colour sees, is exact.
  EXPECT_LT(with_colour.T_W_C.translation().tail<2>().norm(), 0.005);
  EXPECT_LT(rotationAngleDeg(with_colour.T_W_C), 0.2);

  config.track.color_weight = 0.0;
  Mapper geometry_only(config, test::sharedContext());
  for (int i = 0; i < 3; ++i) geometry_only.integrate(texturedWall(in, 0.0), in);
  const TrackResult without = geometry_only.track(moved, in, Eigen::Isometry3d::Identity());
  EXPECT_FALSE(without.ok());
  EXPECT_NE(without.reason.find("ill-conditioned"), std::string::npos) << without.reason;
  // The stated uncertainty says the same: with colour finite and tighter along the depth (z,
  // geometry and colour) than sideways (colour alone); without colour the sideways directions
  // are unconstrained and the worst-direction sigma is far larger.
  ASSERT_TRUE(with_colour.covariance.allFinite());
  EXPECT_GT(with_colour.translation_sigma_m, 0.0);
  EXPECT_LT(with_colour.covariance(2, 2), with_colour.covariance(0, 0));
  EXPECT_GT(without.translation_sigma_m, 10.0 * with_colour.translation_sigma_m);
  std::printf("stated translation sigma: with colour %.2e m (x %.2e, z %.2e), without %.2e m\n",
              with_colour.translation_sigma_m, std::sqrt(with_colour.covariance(0, 0)),
              std::sqrt(with_colour.covariance(2, 2)), without.translation_sigma_m);
  const Eigen::Vector3d t = with_colour.T_W_C.translation();
  std::printf("textured wall, 2 cm to the side: with colour (%.4f, %.4f, %.4f) m, %.3f deg (%s); "
              "without: %s\n",
              t.x(), t.y(), t.z(), rotationAngleDeg(with_colour.T_W_C),
              with_colour.ok() ? "ok" : "lost", without.reason.c_str());
}

TEST(TrackCli, FuseTrackWritesTheEstimatedTrajectory) {
  const std::string path = ::testing::TempDir() + "/track_cli_trajectory.txt";
  std::remove(path.c_str());
  apps::FuseOptions options;  // the built-in analytic scene
  options.frames = 6;
  options.track = true;
  options.trajectory_path = path;
  options.quiet = true;
  ASSERT_EQ(apps::runFuse(options), 0);
  const std::vector<tum::TimedPose> poses = tum::readTrajectory(path);
  ASSERT_EQ(poses.size(), 6u);
  const sim::AnalyticDataset truth;
  for (std::size_t i = 0; i < poses.size(); ++i) {
    EXPECT_LT(translationError(poses[i].T_W_C, truth.poses()[i]), 0.005) << "frame " << i;
    EXPECT_NEAR(poses[i].timestamp_s, truth.load(i).timestamp_s, 1e-6);
  }
  options.reference = true;  // tracking runs on the device only
  EXPECT_EQ(apps::runFuse(options), 2);
}

}  // namespace
}  // namespace strata
