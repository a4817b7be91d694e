// Closed-loop exploration of the shipped room in the simulator (short, low resolution), and the
// input errors of `strata explore`.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <limits>

#include "cli/explore_command.h"
#include "strata/explore/exploration_loop.h"
#include "strata/explore/history_planner.h"
#include "strata/explore/nbvp_planner.h"
#include "fusion_fixture.h"
#include "strata/sim/world/world.h"
#include "strata/sim/world/world_paths.h"
#include "test_utils.h"

namespace strata::explore {
namespace {

struct RoomRun {
  ExplorationResult result;
  std::size_t reachable = 0;
};

RoomRun exploreRoom(ExplorationPlanner& planner, double time_limit_s,
                    ExplorationConfig config = {}) {
  const sim::World world = sim::World::load(sim::findWorld("room"));
  config.time_limit_s = time_limit_s;
  config.eval_period_s = 5.0;
  const Eigen::Vector3f start = defaultStart(world, 1.2f, config);
  const Eigen::AlignedBox3d b = world.bounds();
  const ExplorationTruth truth(world, {b.min().cast<float>(), b.max().cast<float>()}, start,
                               config.voxel_size_m);
  ExplorationLoop loop(world, truth, config, {start, 0.0f}, test::sharedContext());
  RoomRun run;
  run.result = loop.run(planner);
  run.reachable = truth.reachableVoxels();
  return run;
}

TEST(ExplorationLoop, HistoryPlannerExploresTheRoomWithoutCollision) {
  HistoryPlanner planner(HistoryConfig{});
  const RoomRun run = exploreRoom(planner, 40.0);
  // The room's free space at 0.1 m: 5 x 4 x 2.5 m less the furniture.
  EXPECT_GT(run.reachable, 40000u);
  EXPECT_LT(run.reachable, 50000u);
  EXPECT_GT(run.result.explored_fraction, 0.85);
  EXPECT_EQ(run.result.collisions(), 0);
  EXPECT_GE(run.result.min_clearance_m, 0.3f);
  EXPECT_GT(run.result.path_length_m, 3.0);
  ASSERT_FALSE(run.result.curve.empty());
  // The share never falls (observed voxels stay observed) and grows from the start.
  for (std::size_t i = 1; i < run.result.curve.size(); ++i) {
    EXPECT_GE(run.result.curve[i].explored_fraction, run.result.curve[i - 1].explored_fraction);
  }
  EXPECT_GT(run.result.explored_fraction, run.result.curve.front().explored_fraction + 0.3);
}

TEST(ExplorationLoop, NbvpExploresTheRoomWithoutCollision) {
  NbvpPlanner planner(NbvpConfig{});
  const RoomRun run = exploreRoom(planner, 40.0);
  EXPECT_GT(run.result.explored_fraction, 0.7);
  EXPECT_EQ(run.result.collisions(), 0);
  EXPECT_GT(run.result.steps.size(), 5u);
}

/// Asks once for a straight flight 20 m along +x (through the room's wall), then is finished.
class ThroughTheWallPlanner final : public ExplorationPlanner {
 public:
  ExplorationStep plan(const ExplorationState& state) override {
    ExplorationStep step;
    step.finished = asked_++ > 0;
    if (!step.finished) {
      step.path = {{state.pose.position_W + Eigen::Vector3f(20.0f, 0.0f, 0.0f), 0.0f}};
    }
    return step;
  }
  std::string name() const override { return "through-the-wall"; }

 private:
  int asked_ = 0;
};

// The wall (and the unknown space behind it) lie within the checks' 2 m lookahead from the
// first check in flight: the robot brakes at once, stops clear of everything and asks again.
TEST(ExplorationLoop, InFlightChecksBrakeWhenThePathAheadIsBlocked) {
  ThroughTheWallPlanner planner;
  const RoomRun braked = exploreRoom(planner, 30.0);
  EXPECT_GE(braked.result.inflight_checks, 1u);
  EXPECT_EQ(braked.result.brakes, 1u);
  EXPECT_EQ(braked.result.stop_reason, "no gain") << "asked again once at rest";
  EXPECT_EQ(braked.result.collisions(), 0);
  EXPECT_GE(braked.result.min_clearance_m, 0.3f);
  EXPECT_GT(braked.result.path_length_m, 0.0);
  EXPECT_LT(braked.result.path_length_m, 0.6) << "within the stopping distance of the start";

  ExplorationConfig unchecked;
  unchecked.inflight_checks = false;
  ThroughTheWallPlanner blind;
  const RoomRun crashed = exploreRoom(blind, 30.0, unchecked);
  EXPECT_EQ(crashed.result.inflight_checks, 0u);
  EXPECT_EQ(crashed.result.brakes, 0u);
  EXPECT_GE(crashed.result.collisions(), 1) << "without the checks the path meets the wall";
}

TEST(ExplorationLoop, TheNoddingCameraTilesTwiceTheVerticalFieldOfView) {
  const ExplorationConfig config;
  EXPECT_FLOAT_EQ(framePitch(config, 0), config.camera_pitch_rad);
  EXPECT_FLOAT_EQ(framePitch(config, 1), -config.camera_pitch_rad);
  const RobotPose pose{Eigen::Vector3f(1.0f, 2.0f, 1.2f), 0.5f};
  const Eigen::Isometry3d up = cameraPose(pose, 0.4f);
  const Eigen::Vector3d axis = up.linear().col(2);
  // (sines and cosines of the float angles are float: 1e-7)
  EXPECT_NEAR(std::asin(axis.z()), 0.4, 1e-6);  // pitched up by 0.4 rad
  EXPECT_NEAR(std::atan2(axis.y(), axis.x()), 0.5, 1e-6);  // along the yaw
  EXPECT_NEAR((up.linear().transpose() * up.linear() - Eigen::Matrix3d::Identity()).norm(), 0.0,
              1e-6);
  EXPECT_NEAR(up.linear().determinant(), 1.0, 1e-6);
  EXPECT_LT(up.linear().col(1).z(), 0.0) << "image y still points down";
  // 160 x 120 at 60 degrees: 46.8 degrees vertically; the two pitches tile +-46.8 degrees, the
  // gain model's vertical field of view.
  const double half_v = std::atan(std::tan(0.5 * config.gain.horizontal_fov_rad) * 120.0 / 160.0);
  EXPECT_NEAR(config.camera_pitch_rad, half_v, 0.01);
  EXPECT_NEAR(config.gain.vertical_fov_rad, 4.0 * half_v, 0.01);
}

TEST(ExplorationLoop, DefaultVoxelIsFineWhereTheWorldIsSmall) {
  // Bounds of the shipped worlds: room (5 x 4 x 2.5 m rooms) and office (12 x 10 x 2.6 m) hold
  // under 4M voxels of 5 cm, the dead end (32 x 8 x 2.5 m) and the warehouse (20 x 8 x 5 m) over.
  EXPECT_FLOAT_EQ(defaultVoxelSize(sim::World::load(sim::findWorld("room"))), 0.05f);
  EXPECT_FLOAT_EQ(defaultVoxelSize(sim::World::load(sim::findWorld("office"))), 0.05f);
  EXPECT_FLOAT_EQ(defaultVoxelSize(sim::World::load(sim::findWorld("deadend"))), 0.1f);
  EXPECT_FLOAT_EQ(defaultVoxelSize(sim::World::load(sim::findWorld("warehouse"))), 0.1f);
}

TEST(ExploreCommand, BadInputIsAnInputError) {
  const std::filesystem::path out = test::freshTempDir("explore_cli");
  apps::ExploreOptions o;
  o.out_dir = out.string();
  o.world_path = (out / "missing.yaml").string();
  EXPECT_EQ(apps::runExplore(o), 2);
  o.world_path = sim::findWorld("room");
  o.start = "1,2";
  EXPECT_EQ(apps::runExplore(o), 2);
  o.start = "2.5,2,nan";
  EXPECT_EQ(apps::runExplore(o), 2);
  o.start = "0.05,0.05,1.2";  // against the walls: no room for the robot
  EXPECT_EQ(apps::runExplore(o), 2);
  o.start.clear();
  o.planner = "frontier";
  EXPECT_EQ(apps::runExplore(o), 2);
  o.planner = "history";
  o.voxel_size_m = -0.1f;
  EXPECT_EQ(apps::runExplore(o), 2);
  o.voxel_size_m = 0.1f;
  o.tree_box = "4,4,0";  // a flat box
  EXPECT_EQ(apps::runExplore(o), 2);
  o.tree_box = "4,4";
  EXPECT_EQ(apps::runExplore(o), 2);
  o.tree_box.clear();
  o.start_yaw_deg = std::numeric_limits<double>::infinity();
  EXPECT_EQ(apps::runExplore(o), 2);
  o.start_yaw_deg = 0.0;
  o.dead_end_mouth = "10,4";  // a mouth without a dead end
  EXPECT_EQ(apps::runExplore(o), 2);
  o.dead_end = "5,5,1,1";  // X0 > X1
  EXPECT_EQ(apps::runExplore(o), 2);
  o.dead_end = "1,1,9,7";  // holds the default start: where does it open?
  o.dead_end_mouth.clear();
  EXPECT_EQ(apps::runExplore(o), 2);
  o.dead_end_mouth = "1,x";
  EXPECT_EQ(apps::runExplore(o), 2);
}

}  // namespace
}  // namespace strata::explore
