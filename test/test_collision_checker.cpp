// Batched collision checks of a spherical robot: the host (EsdfQuery) and device (query kernel)
// checkers against each other on one device-built ESDF, and against the analytic geometry; the
// RRT* planner on the device checker.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "strata/esdf/esdf.h"
#include "fusion_fixture.h"
#include "strata/map/device_tsdf_map.h"
#include "strata/plan/collision_checker.h"
#include "strata/plan/rrt_planner.h"
#include "plan_test_scene.h"

namespace strata::plan {
namespace {

using test::Ball;
using test::Box;

constexpr float kVoxelM = 0.05f;

/// A ball and a box in blocks -3..2 (x, y, z in [-1.2, 1.2)), every voxel observed.
struct Scene {
  std::vector<Box> boxes{{{-0.8f, -0.6f, -0.5f}, {-0.4f, 0.5f, 0.4f}}};
  std::vector<Ball> balls{{{0.3f, 0.2f, 0.0f}, 0.35f}};
  float distance(const Eigen::Vector3f& p) const { return test::sceneDistance(p, boxes, balls); }
};

/// The scene's ESDF made on the device, and its host copy.
struct DeviceScene {
  Scene scene;
  test::AnalyticMap analytic;
  std::unique_ptr<DeviceTsdfMap> tsdf;
  std::unique_ptr<DeviceEsdf> esdf;
  EsdfMap downloaded;
};

std::unique_ptr<DeviceScene> makeDeviceScene(const Scene& scene, const Eigen::Vector3i& lo,
                                             const Eigen::Vector3i& hi, float voxel_m) {
  auto out = std::make_unique<DeviceScene>();
  out->scene = scene;
  out->analytic = test::makeAnalyticMap(
      [scene](const Eigen::Vector3f& p) { return scene.distance(p); }, lo, hi, voxel_m, 1.0f);
  vk::Context& context = test::sharedContext();
  out->tsdf = std::make_unique<DeviceTsdfMap>(context, out->analytic.tsdf.config());
  out->tsdf->upload(out->analytic.tsdf);
  out->esdf = std::make_unique<DeviceEsdf>(context, *out->tsdf, out->analytic.esdf.config);
  out->esdf->updateAll();
  out->esdf->download(out->downloaded);
  return out;
}

std::vector<EsdfSegment> randomSegments(int count, float half_extent_m, float max_length_m,
                                        unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> coord(-half_extent_m, half_extent_m);
  std::uniform_real_distribution<float> step(-max_length_m, max_length_m);
  std::vector<EsdfSegment> out;
  while (static_cast<int>(out.size()) < count) {
    const Eigen::Vector3f a(coord(rng), coord(rng), coord(rng));
    const Eigen::Vector3f b = a + Eigen::Vector3f(step(rng), step(rng), step(rng)) * 0.577f;
    if ((b.array().abs() <= half_extent_m).all()) out.push_back({a, b});
  }
  return out;
}

TEST(CollisionChecker, HostAndDeviceGiveTheSameFlags) {
  const auto scene = makeDeviceScene(Scene{}, {-3, -3, -3}, {2, 2, 2}, kVoxelM);
  HostCollisionChecker host(scene->downloaded);
  DeviceCollisionChecker device(test::sharedContext(), *scene->esdf);
  // Segments reaching past the map: unallocated space counts under kOccupied only.
  const std::vector<EsdfSegment> segments = randomSegments(600, 1.15f, 0.8f, 7);
  std::vector<Eigen::Vector3f> centres;
  for (const EsdfSegment& s : segments) centres.push_back(s.a_W);
  for (const UnknownPolicy policy : {UnknownPolicy::kOccupied, UnknownPolicy::kFree}) {
    for (const float radius : {0.0f, 0.1f, 0.3f}) {
      const auto host_segments = host.segmentsFree(segments, radius, policy);
      EXPECT_EQ(host_segments, device.segmentsFree(segments, radius, policy)) << radius;
      EXPECT_EQ(host.spheresFree(centres, radius, policy),
                device.spheresFree(centres, radius, policy))
          << radius;
      // Both outcomes occur: the comparison is not between two all-free (or all-blocked) lists.
      const auto free_count = std::count(host_segments.begin(), host_segments.end(), 1);
      EXPECT_GT(free_count, 30) << radius;
      EXPECT_LT(free_count, static_cast<long>(segments.size()) - 30) << radius;
    }
  }
  EXPECT_GT(device.deviceMs(), 0.0);
  EXPECT_EQ(host.spheresTested(), device.spheresTested());
}

// Ground truth. Obstacle voxel centres lie within one voxel outside the surface (sites: |tsdf| <=
// 1 voxel) and always within sqrt(3)/2 voxel of any surface point, so a capsule reaching below
// radius - 1 voxel of the surface is never free. The sphere test is a lower bound that may lose
// the distance from the query to its voxel centre twice (sqrt(3) voxels) plus the site shell
// (1 voxel) and the sample radius' h/2 term: a capsule clear by more than radius + 3 voxels is
// always free.
void expectGroundTruth(CollisionChecker& checker, const Scene& scene, const char* name) {
  const std::vector<EsdfSegment> segments = randomSegments(800, 0.8f, 0.8f, 11);
  const float radius = 0.1f;
  const auto free = checker.segmentsFree(segments, radius, UnknownPolicy::kOccupied);
  int must_be_free = 0, must_be_blocked = 0;
  for (std::size_t i = 0; i < segments.size(); ++i) {
    const float d =
        test::segmentDistance([&](const Eigen::Vector3f& p) { return scene.distance(p); },
                              segments[i].a_W, segments[i].b_W);
    if (d > radius + 3.0f * kVoxelM) {
      ++must_be_free;
      EXPECT_EQ(free[i], 1) << name << " segment " << i << " clear by " << d;
    } else if (d < radius - kVoxelM) {
      ++must_be_blocked;
      EXPECT_EQ(free[i], 0) << name << " segment " << i << " clear by " << d;
    }
  }
  EXPECT_GT(must_be_free, 100) << name;
  EXPECT_GT(must_be_blocked, 100) << name;
}

TEST(CollisionChecker, BothAgreeWithTheAnalyticGeometry) {
  const auto scene = makeDeviceScene(Scene{}, {-3, -3, -3}, {2, 2, 2}, kVoxelM);
  HostCollisionChecker reference(scene->analytic.esdf);
  HostCollisionChecker host(scene->downloaded);
  DeviceCollisionChecker device(test::sharedContext(), *scene->esdf);
  expectGroundTruth(reference, scene->scene, "host on the reference ESDF");
  expectGroundTruth(host, scene->scene, "host on the device ESDF");
  expectGroundTruth(device, scene->scene, "device");
}

TEST(CollisionChecker, MinClearanceIsTheAnalyticDistanceWithinAVoxel) {
  const auto scene = makeDeviceScene(Scene{}, {-3, -3, -3}, {2, 2, 2}, kVoxelM);
  HostCollisionChecker host(scene->downloaded);
  DeviceCollisionChecker device(test::sharedContext(), *scene->esdf);
  // Polylines passing the ball and the box at 0.1 .. 0.5 m (all within the ESDF's 1 m reach).
  const std::vector<std::vector<Eigen::Vector3f>> paths{
      {{0.3f, -0.5f, 0.0f}, {0.95f, 0.2f, 0.0f}, {0.3f, 0.85f, 0.1f}},
      {{-0.3f, -0.9f, -0.2f}, {-0.25f, 0.7f, 0.0f}},
      {{0.0f, -0.9f, 0.6f}, {0.0f, 0.9f, 0.6f}, {0.6f, 0.9f, -0.6f}},
  };
  for (const auto& path : paths) {
    float truth = std::numeric_limits<float>::infinity();
    for (std::size_t i = 1; i < path.size(); ++i) {
      truth = std::min(
          truth,
          test::segmentDistance([&](const Eigen::Vector3f& p) { return scene->scene.distance(p); },
                                path[i - 1], path[i]));
    }
    ASSERT_GT(truth, 0.05f);
    ASSERT_LT(truth, 0.6f);
    EXPECT_NEAR(host.minClearance(path), truth, kVoxelM);
    EXPECT_NEAR(device.minClearance(path), truth, kVoxelM);
  }
}

TEST(CollisionChecker, RrtPlansThroughTheDoorOnTheDevice) {
  const test::RoomScene& room = test::roomScene(true);
  vk::Context& context = test::sharedContext();
  DeviceTsdfMap tsdf(context, room.map.tsdf.config());
  tsdf.upload(room.map.tsdf);
  DeviceEsdf esdf(context, tsdf, room.map.esdf.config);
  esdf.updateAll();
  DeviceCollisionChecker device(context, esdf);
  RrtOptions options;
  options.bounds_W = esdfBounds(room.map.esdf);
  options.max_iterations = 400;  // the device checks one motion per dispatch: keep it short
  RrtPlanner planner(device, options);
  PlanRequest request;
  request.start_W = {-2.0f, -1.2f, 0.8f};
  request.goal_W = {2.0f, -1.2f, 0.8f};
  request.radius_m = 0.25f;
  request.time_budget_s = 60.0;
  const PlanResult result = planner.plan(request);
  ASSERT_TRUE(result.success) << result.message;
  // The same path, shortened and checked on the host copy, is free there too.
  EsdfMap downloaded;
  esdf.download(downloaded);
  HostCollisionChecker host(downloaded);
  EXPECT_TRUE(host.pathFree(result.path_W, request.radius_m, request.unknown));
  for (std::size_t i = 1; i < result.path_W.size(); ++i) {
    EXPECT_GE(test::segmentDistance([&](const Eigen::Vector3f& p) { return room.distance(p); },
                                    result.path_W[i - 1], result.path_W[i]),
              request.radius_m);
  }
  EXPECT_GT(planner.lastStats().device_ms, 0.0);
  EXPECT_GT(planner.lastStats().batches, 100u);
}

}  // namespace
}  // namespace strata::plan
