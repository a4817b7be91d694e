// Grid A* on an analytic room with a wall and a door: the path through the door, its length
// against the analytic shortest path, its clearance against the analytic geometry, no path with
// the door closed, start or goal in collision or outside the map refused.
#include <gtest/gtest.h>

#include <cmath>

#include "strata/plan/collision_checker.h"
#include "strata/plan/grid_astar.h"
#include "plan_room_scene.h"

namespace strata::plan {
namespace {

using test::PlanRoom;

constexpr float kRadiusM = 0.2f;
// Voxel centres on both sides of the wall, below the door (symmetric about x = 2).
const Eigen::Vector3f kStart(1.05f, 0.55f, 0.55f);
const Eigen::Vector3f kGoal(2.95f, 0.55f, 0.55f);

/// Shortest path in the plane from kStart to kGoal for a disc of radius r around a jamb whose
/// top corners are (x0, y0) and (x1, y0) (the wall below them): tangent, arc around the corner,
/// along the top, arc, tangent (symmetric about x = 2).
double analyticLength(double x0, double x1, double y0, double r) {
  const Eigen::Vector2d s(kStart.x(), kStart.y()), c(x0, y0);
  const double dist = (s - c).norm();
  const double tangent = std::sqrt(dist * dist - r * r);
  // The tangent point on the side facing the door, then the arc up to straight above c.
  const double tangent_angle = std::atan2(s.y() - c.y(), s.x() - c.x()) - std::acos(r / dist);
  const double arc = std::abs(M_PI / 2 - (tangent_angle + 2 * M_PI));
  return 2.0 * (tangent + r * arc) + (x1 - x0);
}

/// Smallest analytic distance to the room's surfaces along the path, sampled every 5 mm.
double analyticClearance(const PlanRoom& room, const std::vector<Eigen::Vector3f>& path) {
  double best = 1e9;
  for (std::size_t i = 1; i < path.size(); ++i) {
    const Eigen::Vector3d a = path[i - 1].cast<double>(), b = path[i].cast<double>();
    const int n = std::max(1, static_cast<int>(std::ceil((b - a).norm() / 0.005)));
    for (int k = 0; k <= n; ++k) best = std::min(best, room.signedDistance(a + (b - a) * k / n));
  }
  return best;
}

class PlanGridTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    open_ = new EsdfMap(PlanRoom{}.esdf());
    PlanRoom closed;
    closed.door_open = false;
    closed_ = new EsdfMap(closed.esdf());
  }
  static void TearDownTestSuite() {
    delete open_;
    delete closed_;
  }
  static PlanRequest request(const Eigen::Vector3f& start, const Eigen::Vector3f& goal) {
    PlanRequest r;
    r.start_W = start;
    r.goal_W = goal;
    r.radius_m = kRadiusM;
    return r;
  }
  static EsdfMap* open_;
  static EsdfMap* closed_;
};
EsdfMap* PlanGridTest::open_ = nullptr;
EsdfMap* PlanGridTest::closed_ = nullptr;

TEST_F(PlanGridTest, FindsThePathThroughTheDoor) {
  HostCollisionChecker checker(*open_);
  GridAStarPlanner planner(*open_, checker);
  const PlanResult result = planner.plan(request(kStart, kGoal));
  ASSERT_TRUE(result.success) << result.message;
  EXPECT_EQ(result.path_W.front(), kStart);
  EXPECT_EQ(result.path_W.back(), kGoal);
  // Through the door: some point of the path lies in the wall's x range at a door y.
  bool through_door = false;
  for (std::size_t i = 1; i < result.path_W.size(); ++i) {
    const Eigen::Vector3f a = result.path_W[i - 1], b = result.path_W[i];
    for (int k = 0; k <= 100; ++k) {
      const Eigen::Vector3f p = a + (b - a) * (k / 100.0f);
      through_door |= p.x() > PlanRoom::kWallX0 && p.x() < PlanRoom::kWallX1 &&
                      p.y() > PlanRoom::kDoorY0 && p.y() < PlanRoom::kDoorY1;
    }
  }
  EXPECT_TRUE(through_door);
  EXPECT_NEAR(result.length_m, pathLength(result.path_W), 1e-4);
  EXPECT_GT(result.collision_checks, 0u);
  EXPECT_GT(planner.memoryBytes(), planner.buildStats().cells);
  EXPECT_GT(planner.buildStats().build_ms, 0.0);
  // Pruned: far fewer points than the voxel steps of the route (about 40).
  EXPECT_LE(result.path_W.size(), 8u);
  // Free under the planner's own capsule test and the ESDF clearance it reports.
  EXPECT_TRUE(checker.pathFree(result.path_W, kRadiusM, UnknownPolicy::kOccupied));
  EXPECT_GT(result.min_clearance_m, kRadiusM);
}

TEST_F(PlanGridTest, LengthNearTheAnalyticShortestPath) {
  HostCollisionChecker checker(*open_);
  GridAStarPlanner planner(*open_, checker);
  const PlanResult result = planner.plan(request(kStart, kGoal));
  ASSERT_TRUE(result.success) << result.message;
  // Never shorter than the true shortest path for the radius.
  const double shortest_m =
      analyticLength(PlanRoom::kWallX0, PlanRoom::kWallX1, PlanRoom::kDoorY0, kRadiusM);
  EXPECT_GT(result.length_m, shortest_m - 1e-3);
  // The collision model is conservative: the ESDF's obstacles are site voxel centres up to half a
  // voxel in front of the surfaces, and the sphere test between voxel centres subtracts the
  // distance to the nearest centre (up to sqrt(3)/2 voxel). The shortest path of that model,
  // plus 3 % for waypoints that start on voxel centres, bounds the length from above.
  const double h = 0.5 * PlanRoom::kVoxelM;
  const double model_m = analyticLength(PlanRoom::kWallX0 - h, PlanRoom::kWallX1 + h,
                                        PlanRoom::kDoorY0 + h, kRadiusM + std::sqrt(3.0) * h);
  EXPECT_LT(result.length_m, 1.03 * model_m);
  EXPECT_LT(result.length_m, 1.12 * shortest_m);
}

TEST_F(PlanGridTest, PathKeepsTheRadiusFromTheAnalyticGeometry) {
  HostCollisionChecker checker(*open_);
  GridAStarPlanner planner(*open_, checker);
  const PlanRoom room;
  for (const auto& [start, goal] :
       {std::pair{kStart, kGoal}, std::pair{Eigen::Vector3f(0.45f, 2.55f, 0.75f), kGoal},
        std::pair{Eigen::Vector3f(3.55f, 2.65f, 0.35f), Eigen::Vector3f(0.35f, 0.35f, 0.85f)}}) {
    const PlanResult result = planner.plan(request(start, goal));
    ASSERT_TRUE(result.success) << result.message;
    EXPECT_GE(analyticClearance(room, result.path_W), kRadiusM);
  }
}

TEST_F(PlanGridTest, NoPathWhenTheDoorIsClosed) {
  HostCollisionChecker checker(*closed_);
  GridAStarPlanner planner(*closed_, checker);
  const PlanResult result = planner.plan(request(kStart, kGoal));
  EXPECT_FALSE(result.success);
  EXPECT_TRUE(result.path_W.empty());
  EXPECT_NE(result.message.find("not connected"), std::string::npos) << result.message;
  // Both sides still reach their own side.
  EXPECT_TRUE(planner.plan(request(kStart, Eigen::Vector3f(0.45f, 2.55f, 0.55f))).success);
}

TEST_F(PlanGridTest, RefusesEndpointsInCollisionOrOutside) {
  HostCollisionChecker checker(*open_);
  GridAStarPlanner planner(*open_, checker);
  const PlanResult in_wall = planner.plan(request(Eigen::Vector3f(2.05f, 0.55f, 0.55f), kGoal));
  EXPECT_FALSE(in_wall.success);
  EXPECT_NE(in_wall.message.find("start"), std::string::npos) << in_wall.message;
  EXPECT_NE(in_wall.message.find("in collision"), std::string::npos) << in_wall.message;
  // Free of the wall but closer than the radius to it.
  const PlanResult too_close = planner.plan(request(kStart, Eigen::Vector3f(2.25f, 0.55f, 0.55f)));
  EXPECT_FALSE(too_close.success);
  EXPECT_NE(too_close.message.find("goal"), std::string::npos) << too_close.message;
  const PlanResult outside = planner.plan(request(kStart, Eigen::Vector3f(9.0f, 0.5f, 0.5f)));
  EXPECT_FALSE(outside.success);
  EXPECT_NE(outside.message.find("outside the map"), std::string::npos) << outside.message;
  const PlanResult nan = planner.plan(request(Eigen::Vector3f(NAN, 0.5f, 0.5f), kGoal));
  EXPECT_FALSE(nan.success);
  EXPECT_FALSE(nan.message.empty());
}

TEST_F(PlanGridTest, GridIsBuiltOncePerRadiusAndPolicy) {
  HostCollisionChecker checker(*open_);
  GridAStarPlanner planner(*open_, checker);
  const TraversabilityGrid& a = planner.prepare(kRadiusM, UnknownPolicy::kOccupied);
  EXPECT_EQ(&a, &planner.prepare(kRadiusM, UnknownPolicy::kOccupied));
  const TraversabilityGrid& b = planner.prepare(0.35f, UnknownPolicy::kOccupied);
  EXPECT_NE(&a, &b);
  // A larger robot fits in fewer places.
  EXPECT_LT(b.traversableCount(), a.traversableCount());
  EXPECT_GT(b.traversableCount(), 0u);
}

}  // namespace
}  // namespace strata::plan
