// The analytic scene: exact signed distance, exact depth, the default trajectory and dataset.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <string>

#include "strata/core/error.h"
#include "strata/io/open_dataset.h"
#include "strata/io/tum_writer.h"
#include "strata/sim/analytic_dataset.h"
#include "strata/sim/analytic_scene.h"
#include "strata/sim/default_scene.h"

namespace strata::sim {
namespace {

constexpr double kPi = 3.14159265358979323846;

Eigen::Vector3d backProject(const CameraIntrinsics& k, int u, int v, double depth_m) {
  return Eigen::Vector3d((u - static_cast<double>(k.cx_px)) / k.fx_px * depth_m,
                         (v - static_cast<double>(k.cy_px)) / k.fy_px * depth_m, depth_m);
}

AnalyticScene floorOnly() {
  AnalyticScene scene;
  scene.add(Plane{Eigen::Vector3d::Zero(), Eigen::Vector3d::UnitZ(), {100, 100, 100}});
  return scene;
}

TEST(AnalyticScene, SignedDistanceOfKnownPoints) {
  AnalyticScene scene = floorOnly();
  EXPECT_DOUBLE_EQ(scene.signedDistance(Eigen::Vector3d(0.3, -7.0, 0.75)), 0.75);
  EXPECT_DOUBLE_EQ(scene.signedDistance(Eigen::Vector3d(1.0, 2.0, -0.5)), -0.5);

  const Eigen::Vector3d centre(1.0, 1.0, 2.0);
  scene.add(Sphere{centre, 0.3, {0, 255, 0}});
  EXPECT_DOUBLE_EQ(scene.signedDistance(centre), -0.3);
  EXPECT_NEAR(scene.signedDistance(Eigen::Vector3d(centre + Eigen::Vector3d(0.0, 0.6, 0.0))), 0.3,
              1e-12);

  Box box;
  box.centre_W = Eigen::Vector3d(-1.0, 0.0, 1.0);
  box.half_extents_m = Eigen::Vector3d(0.2, 0.15, 0.25);
  box.R_W_B = Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 1, 0).normalized()).toRotationMatrix();
  scene.add(box);
  const auto inBox = [&](double x, double y, double z) {
    return Eigen::Vector3d(box.centre_W + box.R_W_B * Eigen::Vector3d(x, y, z));
  };
  EXPECT_NEAR(scene.signedDistance(inBox(0, 0, 0)), -0.15, 1e-12);
  EXPECT_NEAR(scene.signedDistance(inBox(0.1, 0, 0.05)), -0.1, 1e-12);
  EXPECT_NEAR(scene.signedDistance(inBox(0.2 + 0.3, 0.15 + 0.4, 0)), 0.5, 1e-12);  // off an edge
  EXPECT_NEAR(scene.signedDistance(Eigen::Vector3f(inBox(0, 0.25, 0).cast<float>())), 0.1f, 1e-6f);

  const AnalyticScene room = makeDefaultScene();
  EXPECT_NEAR(room.signedDistance(Eigen::Vector3d(0.0, 0.0, 0.2)), -0.2, 1e-12);  // sphere centre
  EXPECT_NEAR(room.signedDistance(Eigen::Vector3d(1.5, -1.5, 0.1)), 0.1, 1e-12);  // above floor
}

TEST(AnalyticScene, RejectsDegeneratePrimitives) {
  AnalyticScene scene;
  EXPECT_THROW(scene.add(Plane{Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero(), {}}), InputError);
  EXPECT_THROW(scene.add(Sphere{Eigen::Vector3d::Zero(), 0.0, {}}), InputError);
  Box box;
  box.R_W_B(0, 0) = 2.0;
  EXPECT_THROW(scene.add(box), InputError);
}

TEST(AnalyticScene, CastRaySeesSolidsFromOutsideOnly) {
  AnalyticScene scene = floorOnly();
  scene.add(Sphere{Eigen::Vector3d(0, 0, 1), 0.5, {255, 0, 0}});
  AnalyticHit hit;
  ASSERT_TRUE(scene.castRay(Eigen::Vector3d(0, 0, 3), -Eigen::Vector3d::UnitZ(), 10.0, &hit));
  EXPECT_NEAR(hit.t_m, 1.5, 1e-12);
  EXPECT_NEAR((hit.normal_W - Eigen::Vector3d::UnitZ()).norm(), 0.0, 1e-12);
  EXPECT_EQ(hit.albedo[0], 255);
  EXPECT_FALSE(scene.castRay(Eigen::Vector3d(0, 0, 3), -Eigen::Vector3d::UnitZ(), 1.4, &hit));
  EXPECT_FALSE(scene.castRay(Eigen::Vector3d(0, 0, 3), Eigen::Vector3d::UnitZ(), 10.0, &hit));
  // From inside the sphere the ray sees the floor, not the sphere's far side.
  ASSERT_TRUE(scene.castRay(Eigen::Vector3d(0, 0, 1), -Eigen::Vector3d::UnitZ(), 10.0, &hit));
  EXPECT_NEAR(hit.t_m, 1.0, 1e-12);
}

TEST(AnalyticScene, DepthEqualsRayPlaneIntersection) {
  const AnalyticScene scene = floorOnly();
  const CameraIntrinsics k;
  // Looking straight down from 1.7 m: every pixel sees the floor at depth 1.7.
  Eigen::Isometry3d down = Eigen::Isometry3d::Identity();
  down.linear() = Eigen::Vector3d(1, -1, -1).asDiagonal();
  down.translation() = Eigen::Vector3d(0.2, 0.1, 1.7);
  const DepthImage flat = scene.renderDepth(k, down, 10.0f);
  for (float d : flat.depth_m) ASSERT_NEAR(d, 1.7f, 1e-6f);

  // Oblique view: intersect each pixel ray with z = 0 by hand.
  const Eigen::Isometry3d T_W_C = lookAt(Eigen::Vector3d(0.3, -2.0, 1.4), Eigen::Vector3d(0, 0, 0));
  const DepthImage depth = scene.renderDepth(k, T_W_C, 20.0f);
  for (const auto& [u, v] : {std::pair{0, 479}, {320, 240}, {639, 300}, {17, 401}}) {
    const Eigen::Vector3d dir_W = T_W_C.linear() * backProject(k, u, v, 1.0);
    const double t = -T_W_C.translation().z() / dir_W.z();  // p = o + t * dir_W, p_z = 0
    const double expected_depth = t;                        // dir_W has camera-frame z = 1
    EXPECT_NEAR(depth.at(u, v), expected_depth, 1e-6 * expected_depth) << u << "," << v;
  }
  // Beyond max_depth_m is a miss.
  const DepthImage near = scene.renderDepth(k, T_W_C, 2.5f);
  EXPECT_EQ(near.at(320, 0), 0.0f);
  EXPECT_GT(near.at(320, 479), 0.0f);
}

TEST(AnalyticScene, BackProjectedDepthLiesOnTheSurface) {
  const AnalyticDataset dataset(AnalyticDatasetConfig{12});
  const CameraIntrinsics k = dataset.intrinsics();
  for (std::size_t i : {0u, 5u, 11u}) {
    const RgbdFrame frame = dataset.load(i);
    std::size_t valid = 0;
    double worst = 0.0;
    for (int v = 0; v < k.height_px; ++v) {
      for (int u = 0; u < k.width_px; ++u) {
        const float d = frame.depth.at(u, v);
        if (d == 0.0f) continue;
        ++valid;
        const Eigen::Vector3d p_W = frame.T_W_C * backProject(k, u, v, d);
        worst = std::max(worst, std::abs(dataset.scene().signedDistance(p_W)));
      }
    }
    EXPECT_LT(worst, 1e-4) << "frame " << i;
    EXPECT_GT(valid, static_cast<std::size_t>(0.8 * k.width_px * k.height_px)) << "frame " << i;
  }
}

TEST(AnalyticScene, MostSurfacesSeenAtModerateAngles) {
  const AnalyticScene scene = makeDefaultScene();
  const CameraIntrinsics k;
  std::size_t hits = 0, moderate = 0;
  for (const Eigen::Isometry3d& T_W_C : makeDefaultTrajectory(5)) {
    for (int v = 0; v < k.height_px; v += 8) {
      for (int u = 0; u < k.width_px; u += 8) {
        const Eigen::Vector3d dir_W = (T_W_C.linear() * backProject(k, u, v, 1.0)).normalized();
        AnalyticHit hit;
        if (!scene.castRay(T_W_C.translation(), dir_W, 10.0, &hit)) continue;
        ++hits;
        if (-dir_W.dot(hit.normal_W) > std::cos(60.0 * kPi / 180.0)) ++moderate;
      }
    }
  }
  EXPECT_GT(moderate, 0.6 * hits) << moderate << " of " << hits;
}

TEST(AnalyticScene, TrajectoryPosesAreRotationsLookingAtTheCentre) {
  const std::vector<Eigen::Isometry3d> poses = makeDefaultTrajectory(60);
  ASSERT_EQ(poses.size(), 60u);
  for (const Eigen::Isometry3d& T_W_C : poses) {
    const Eigen::Matrix3d R = T_W_C.linear();
    EXPECT_LT((R.transpose() * R - Eigen::Matrix3d::Identity()).norm(), 1e-12);
    EXPECT_NEAR(R.determinant(), 1.0, 1e-12);
    EXPECT_NO_THROW(validatePose(T_W_C, "trajectory"));
    EXPECT_NEAR(T_W_C.translation().z(), 1.4, 1e-12);
    const Eigen::Vector3d to_centre = defaultSceneCentre() - T_W_C.translation();
    EXPECT_NEAR(R.col(2).dot(to_centre.normalized()), 1.0, 1e-12);  // optical axis on the centre
    EXPECT_LT(R.col(1).z(), 0.0);                                   // image y points down
    EXPECT_NEAR(to_centre.head<2>().norm(), 2.0, 1e-9);
  }
  EXPECT_THROW(makeDefaultTrajectory(0), InputError);
}

TEST(AnalyticScene, DatasetFramesAreValid) {
  const AnalyticDataset dataset(AnalyticDatasetConfig{8});
  ASSERT_EQ(dataset.size(), 8u);
  for (std::size_t i = 0; i < dataset.size(); ++i) {
    const RgbdFrame frame = dataset.load(i);
    EXPECT_NO_THROW(validateFrame(frame, dataset.intrinsics()));
    EXPECT_EQ(frame.color.width_px, 640);
    EXPECT_NEAR(frame.timestamp_s, i / 30.0, 1e-12);
  }
  EXPECT_THROW(dataset.load(8), InputError);
}

TEST(AnalyticScene, RoundTripThroughTumFolder) {
  const AnalyticDataset dataset(AnalyticDatasetConfig{3});
  std::vector<RgbdFrame> frames;
  for (std::size_t i = 0; i < dataset.size(); ++i) frames.push_back(dataset.load(i));
  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() /
      ("strata_test_analytic_round_trip_" + std::to_string(::getpid()));
  std::filesystem::remove_all(dir);
  writeTumDataset(dir.string(), dataset.intrinsics(), frames);
  const auto loaded = openDataset(dir.string());
  ASSERT_EQ(loaded->size(), frames.size());
  for (std::size_t i = 0; i < frames.size(); ++i) {
    const RgbdFrame frame = loaded->load(i);
    for (std::size_t p = 0; p < frame.depth.depth_m.size(); ++p) {
      ASSERT_NEAR(frame.depth.depth_m[p], frames[i].depth.depth_m[p], 0.5 / 5000 + 1e-6);
    }
    EXPECT_TRUE(frame.color.rgb == frames[i].color.rgb);
  }
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace strata::sim
