// RRT* on OMPL with the host checker, in a room split by a wall with a door (analytic ESDF), and
// the batched path shortening.
#include <gtest/gtest.h>

#include <cmath>

#include "strata/core/error.h"
#include "strata/plan/collision_checker.h"
#include "strata/plan/path_shortcut.h"
#include "strata/plan/rrt_planner.h"
#include "plan_test_scene.h"

namespace strata::plan {
namespace {

using test::RoomScene;

constexpr float kRadiusM = 0.25f;
const Eigen::Vector3f kStart(-2.0f, -1.2f, 0.8f);
const Eigen::Vector3f kGoal(2.0f, -1.2f, 0.8f);

PlanRequest request(std::uint64_t seed = 1) {
  PlanRequest r;
  r.start_W = kStart;
  r.goal_W = kGoal;
  r.radius_m = kRadiusM;
  r.time_budget_s = 20.0;  // the iteration cap ends the runs well before
  r.seed = seed;
  return r;
}

RrtOptions options(const RoomScene& room, RrtKind kind = RrtKind::kInformedRrtStar) {
  RrtOptions o;
  o.bounds_W = esdfBounds(room.map.esdf);
  o.kind = kind;
  o.max_iterations = 1500;
  return o;
}

/// Tangent from p to the circle (c, r) plus the arc up to the circle's top (+y), in the plane of
/// the room (z is constant): p lies below-left of c.
double tangentAndArc(const Eigen::Vector2d& p, const Eigen::Vector2d& c, double r) {
  const Eigen::Vector2d v = p - c;
  const double d = v.norm();
  double phi = std::atan2(v.y(), v.x());
  if (phi < 0.0) phi += 2.0 * M_PI;
  const double touch = phi - std::acos(r / d);  // angle of the tangent point, going up the left
  return std::sqrt(d * d - r * r) + r * (touch - 0.5 * M_PI);
}

/// The shortest path of a sphere of radius r from start to goal around the near jamb of the door
/// (the wall's corner rounded by r): tangent, arc, across the wall's thickness, arc, tangent.
double analyticShortestM() {
  const Eigen::Vector2d corner_left(-RoomScene::kWallHalfX, RoomScene::kDoorLoY);
  const Eigen::Vector2d corner_right(RoomScene::kWallHalfX, RoomScene::kDoorLoY);
  const Eigen::Vector2d start = kStart.head<2>().cast<double>();
  const Eigen::Vector2d goal = kGoal.head<2>().cast<double>();
  // The right side mirrored in x onto the left case.
  const Eigen::Vector2d goal_mirrored(-(goal.x() - corner_right.x()), goal.y() - corner_right.y());
  return tangentAndArc(start, corner_left, kRadiusM) + 2.0 * RoomScene::kWallHalfX +
         tangentAndArc(goal_mirrored, Eigen::Vector2d::Zero(), kRadiusM);
}

/// Independent of the ESDF: every point of the path (every millimetre) keeps the radius from the
/// walls and from the room's faces (beyond them nothing is allocated: unknown).
void expectFreeInTheRoom(const RoomScene& room, const std::vector<Eigen::Vector3f>& path) {
  const Eigen::AlignedBox3f bounds = esdfBounds(room.map.esdf);
  for (std::size_t i = 1; i < path.size(); ++i) {
    const float d = test::segmentDistance(
        [&](const Eigen::Vector3f& p) {
          const float to_faces =
              std::min((p - bounds.min()).minCoeff(), (bounds.max() - p).minCoeff());
          return std::min(room.distance(p), to_faces);
        },
        path[i - 1], path[i]);
    EXPECT_GE(d, kRadiusM) << "segment " << i;
  }
}

TEST(RrtPlanner, FindsTheDoorAndANearShortestPath) {
  const RoomScene& room = test::roomScene(true);
  HostCollisionChecker checker(room.map.esdf);
  RrtPlanner planner(checker, options(room));
  EXPECT_EQ(planner.name(), "rrt");
  const PlanResult result = planner.plan(request());
  ASSERT_TRUE(result.success) << result.message;
  ASSERT_GE(result.path_W.size(), 3u);
  EXPECT_EQ(result.path_W.front(), kStart);
  EXPECT_EQ(result.path_W.back(), kGoal);
  expectFreeInTheRoom(room, result.path_W);
  // Through the door: where the path crosses x = 0, y is within the door less the radius.
  bool crossed = false;
  for (std::size_t i = 1; i < result.path_W.size(); ++i) {
    const Eigen::Vector3f a = result.path_W[i - 1], b = result.path_W[i];
    if ((a.x() < 0.0f) == (b.x() < 0.0f)) continue;
    const float y = a.y() + (b.y() - a.y()) * (-a.x() / (b.x() - a.x()));
    EXPECT_GT(y, RoomScene::kDoorLoY + kRadiusM);
    EXPECT_LT(y, RoomScene::kDoorHiY - kRadiusM);
    crossed = true;
  }
  EXPECT_TRUE(crossed);
  const double shortest = analyticShortestM();
  EXPECT_NEAR(result.length_m, pathLength(result.path_W), 1e-6);
  EXPECT_GE(result.length_m, shortest - 1e-3);  // a free path cannot beat the true optimum
  EXPECT_LE(result.length_m, 1.2 * shortest);
  EXPECT_LE(result.length_m, planner.lastStats().shortened_from_m + 1e-6);
  EXPECT_GT(result.min_clearance_m, kRadiusM - RoomScene::kVoxelSizeM);
  EXPECT_GT(result.collision_checks, 0u);
  EXPECT_GT(result.planning_ms, 0.0);
  EXPECT_GT(planner.lastStats().motions_checked, 0u);
  EXPECT_GE(planner.lastStats().iterations, 1500u);
}

TEST(RrtPlanner, PlainRrtStarFindsTheDoorToo) {
  const RoomScene& room = test::roomScene(true);
  HostCollisionChecker checker(room.map.esdf);
  RrtPlanner planner(checker, options(room, RrtKind::kRrtStar));
  const PlanResult result = planner.plan(request());
  ASSERT_TRUE(result.success) << result.message;
  expectFreeInTheRoom(room, result.path_W);
  EXPECT_LE(result.length_m, 1.2 * analyticShortestM());
}

TEST(RrtPlanner, NoPathWhenTheDoorIsClosed) {
  const RoomScene& room = test::roomScene(false);
  HostCollisionChecker checker(room.map.esdf);
  RrtOptions o = options(room);
  o.max_iterations = 800;
  RrtPlanner planner(checker, o);
  const PlanResult result = planner.plan(request());
  EXPECT_FALSE(result.success);
  EXPECT_NE(result.message.find("no path"), std::string::npos) << result.message;
  EXPECT_TRUE(result.path_W.empty());
  EXPECT_GT(result.collision_checks, 0u);
}

TEST(RrtPlanner, TheSameSeedGivesTheSamePath) {
  const RoomScene& room = test::roomScene(true);
  HostCollisionChecker checker(room.map.esdf);
  RrtOptions o = options(room);
  o.max_iterations = 600;
  RrtPlanner planner(checker, o);
  const PlanResult first = planner.plan(request(42));
  const double first_raw_m = planner.lastStats().shortened_from_m;
  const PlanResult again = planner.plan(request(42));
  ASSERT_TRUE(first.success && again.success);
  EXPECT_EQ(first.path_W, again.path_W);
  EXPECT_EQ(first_raw_m, planner.lastStats().shortened_from_m);
  // Another seed samples other states: OMPL's own path differs.
  const PlanResult other = planner.plan(request(43));
  ASSERT_TRUE(other.success);
  EXPECT_NE(first_raw_m, planner.lastStats().shortened_from_m);
}

TEST(RrtPlanner, AFreeStraightLineNeedsNoSampling) {
  const RoomScene& room = test::roomScene(true);
  HostCollisionChecker checker(room.map.esdf);
  RrtPlanner planner(checker, options(room));
  PlanRequest r = request();
  r.goal_W = {-1.0f, 1.5f, 0.6f};
  const PlanResult result = planner.plan(r);
  ASSERT_TRUE(result.success);
  EXPECT_EQ(result.path_W, (std::vector<Eigen::Vector3f>{r.start_W, r.goal_W}));
  EXPECT_EQ(planner.lastStats().iterations, 0u);
}

TEST(RrtPlanner, BadEndsAndBadInput) {
  const RoomScene& room = test::roomScene(true);
  HostCollisionChecker checker(room.map.esdf);
  RrtPlanner planner(checker, options(room));
  PlanRequest r = request();
  r.start_W = {0.0f, -1.0f, 0.8f};  // inside the wall
  PlanResult result = planner.plan(r);
  EXPECT_FALSE(result.success);
  EXPECT_NE(result.message.find("start in collision"), std::string::npos) << result.message;
  r = request();
  r.goal_W = {5.0f, 0.0f, 0.8f};
  result = planner.plan(r);
  EXPECT_FALSE(result.success);
  EXPECT_NE(result.message.find("goal outside"), std::string::npos) << result.message;
  r = request();
  r.start_W.x() = std::nanf("");
  EXPECT_THROW(planner.plan(r), InputError);
  RrtOptions empty;
  EXPECT_THROW(RrtPlanner(checker, empty), InputError);
  RrtOptions bad_bias = options(room);
  bad_bias.goal_bias = 1.5;
  EXPECT_THROW(RrtPlanner(checker, bad_bias), InputError);
}

TEST(PathShortcut, AZigzagInFreeSpaceBecomesStraight) {
  const RoomScene& room = test::roomScene(true);
  HostCollisionChecker checker(room.map.esdf);
  const std::vector<Eigen::Vector3f> zigzag{
      {-2.5f, -1.5f, 0.8f}, {-2.0f, 1.0f, 0.6f}, {-1.5f, -1.5f, 1.0f}, {-1.0f, 1.5f, 0.8f}};
  ASSERT_TRUE(checker.pathFree(zigzag, kRadiusM, UnknownPolicy::kOccupied));
  ShortcutStats stats;
  const auto shorter =
      shortcutPath(zigzag, checker, kRadiusM, UnknownPolicy::kOccupied, {}, &stats);
  EXPECT_EQ(shorter, (std::vector<Eigen::Vector3f>{zigzag.front(), zigzag.back()}));
  EXPECT_GE(stats.batches, 2);
  EXPECT_GT(stats.segments, 100u);
}

TEST(PathShortcut, ADetourThroughTheDoorTightensTowardsTheShortest) {
  const RoomScene& room = test::roomScene(true);
  HostCollisionChecker checker(room.map.esdf);
  const std::vector<Eigen::Vector3f> detour{
      kStart, {-1.5f, 2.0f, 0.8f}, {-0.6f, 1.0f, 1.2f}, {0.6f, 1.0f, 0.5f}, {1.0f, 2.0f, 0.8f},
      kGoal};
  ASSERT_TRUE(checker.pathFree(detour, kRadiusM, UnknownPolicy::kOccupied));
  const auto shorter = shortcutPath(detour, checker, kRadiusM, UnknownPolicy::kOccupied);
  EXPECT_TRUE(checker.pathFree(shorter, kRadiusM, UnknownPolicy::kOccupied));
  expectFreeInTheRoom(room, shorter);
  EXPECT_LT(pathLength(shorter), pathLength(detour) - 1.0);
  EXPECT_LE(pathLength(shorter), 1.1 * analyticShortestM());
}

}  // namespace
}  // namespace strata::plan
