// The exploration pieces that need no device: the robot's motion limits, the history graph's
// shortest paths, and the history-aware planner going back to a cached view once the local gain
// is exhausted (a synthetic corridor, a fake collision checker and a fake gain oracle).
#include <gtest/gtest.h>

#include <cmath>
#include <set>

#include "strata/core/error.h"
#include "strata/explore/dead_end.h"
#include "strata/explore/history_graph.h"
#include "strata/explore/history_planner.h"
#include "strata/explore/nbvp_planner.h"
#include "strata/explore/robot_model.h"

namespace strata::explore {
namespace {

TEST(RobotModel, TrapezoidProfileDurations) {
  // Long enough to cruise: L / v + v / a.
  EXPECT_NEAR(TrapezoidProfile(5.0, 1.0, 1.0).duration(), 6.0, 1e-9);
  // Too short to reach full speed: triangular, 2 sqrt(L / a).
  EXPECT_NEAR(TrapezoidProfile(0.5, 1.0, 1.0).duration(), 2.0 * std::sqrt(0.5), 1e-9);
  EXPECT_NEAR(TrapezoidProfile(5.0, 1.0, 1.0).distanceAt(6.0), 5.0, 1e-9);
}

TEST(RobotModel, RespectsSpeedAccelerationAndYawRate) {
  RobotConfig config;
  config.max_speed_mps = 0.8f;
  config.max_accel_mps2 = 0.5f;
  config.max_yaw_rate_radps = 0.6f;
  PathFollower robot(config, {Eigen::Vector3f(0, 0, 1), 0.0f});
  robot.setPath({{Eigen::Vector3f(3, 0, 1), 1.5f},
                 {Eigen::Vector3f(3, 0.3f, 1.2f), -2.5f},
                 {Eigen::Vector3f(-1, 2, 1), 3.0f}});
  const double dt = 0.01;
  Eigen::Vector3f previous = robot.pose().position_W;
  float previous_yaw = robot.pose().yaw_rad;
  double previous_speed = 0.0;
  double t = 0.0;
  for (; t < 120.0 && !robot.done(); t += dt) {
    robot.advance(dt);
    const double speed = (robot.pose().position_W - previous).norm() / dt;
    EXPECT_LE(speed, config.max_speed_mps + 1e-3) << "t = " << t;
    // Acceleration from speeds one step apart (the profile's own speed is exact).
    EXPECT_LE(std::abs(robot.speed() - previous_speed) / dt, config.max_accel_mps2 + 1e-3);
    EXPECT_LE(std::abs(wrapAngle(robot.pose().yaw_rad - previous_yaw)) / dt,
              config.max_yaw_rate_radps + 1e-3);
    previous = robot.pose().position_W;
    previous_yaw = robot.pose().yaw_rad;
    previous_speed = robot.speed();
  }
  ASSERT_TRUE(robot.done());
  EXPECT_LT((robot.pose().position_W - Eigen::Vector3f(-1, 2, 1)).norm(), 1e-4f);
  EXPECT_NEAR(robot.pose().yaw_rad, 3.0f, 1e-4f);
  // No faster than the limits allow: the three segments at least take their profiles' times.
  const double lower = TrapezoidProfile(3.0, 0.8, 0.5).duration() +
                       TrapezoidProfile(std::sqrt(0.13), 0.8, 0.5).duration() +
                       TrapezoidProfile(std::sqrt(16.0 + 3.24), 0.8, 0.5).duration();
  EXPECT_GE(t, lower - 0.02);
}

TEST(RobotModel, TurnsInPlaceAtAWaypoint) {
  PathFollower robot(RobotConfig{}, {Eigen::Vector3f::Zero(), 0.0f});
  robot.setPath({{Eigen::Vector3f::Zero(), 1.5f}});  // no translation, only a turn
  robot.advance(1.0);
  EXPECT_NEAR(robot.pose().yaw_rad, 0.75f, 1e-5f);
  EXPECT_FALSE(robot.atWaypoint());
  robot.advance(1.5);
  EXPECT_NEAR(robot.pose().yaw_rad, 1.5f, 1e-5f);
  EXPECT_TRUE(robot.done());
}

TEST(RobotModel, BrakesAlongItsSegmentToRestWithinTheStoppingDistance) {
  RobotConfig config;
  config.max_speed_mps = 1.0f;
  config.max_accel_mps2 = 0.5f;
  PathFollower robot(config, {Eigen::Vector3f(0, 0, 1), 0.0f});
  robot.setPath({{Eigen::Vector3f(10, 0, 1), 0.0f}, {Eigen::Vector3f(10, 5, 1), 1.0f}});
  robot.advance(4.0);  // 2 s accelerating, 2 s cruising: at x = 3 at 1 m/s
  ASSERT_TRUE(robot.moving());
  ASSERT_NEAR(robot.speed(), 1.0, 1e-6);
  const float braked_at_x = robot.pose().position_W.x();
  EXPECT_NEAR(robot.brake(), 1.0, 1e-6);  // v^2 / (2 a)
  EXPECT_FALSE(robot.moving());
  EXPECT_FALSE(robot.done()) << "still braking";
  double previous_speed = robot.speed();
  for (int i = 0; i < 300 && !robot.done(); ++i) {
    robot.advance(0.01);
    EXPECT_LE(previous_speed - robot.speed(), 0.5 * 0.01 + 1e-6) << "decelerates at max_accel";
    previous_speed = robot.speed();
  }
  ASSERT_TRUE(robot.done());
  EXPECT_TRUE(robot.remaining().empty()) << "the rest of the path is abandoned";
  EXPECT_NEAR(robot.pose().position_W.x(), braked_at_x + 1.0f, 1e-3f);
  EXPECT_NEAR(robot.pose().position_W.y(), 0.0f, 1e-6f) << "along the segment, not to the next";
  EXPECT_EQ(robot.speed(), 0.0);
  // At rest, braking stops at once.
  robot.setPath({{Eigen::Vector3f(0, 0, 1), 0.0f}});
  EXPECT_EQ(robot.brake(), 0.0);
  EXPECT_TRUE(robot.done());
}

TEST(HistoryGraph, ShortestPathAndRerouting) {
  HistoryGraph g;
  const int a = g.addNode({0, 0, 0}), b = g.addNode({1, 0, 0}), c = g.addNode({2, 0, 0});
  const int d = g.addNode({1, 2, 0});
  g.addEdge(a, b);
  g.addEdge(b, c);
  g.addEdge(a, d);
  g.addEdge(d, c);
  std::vector<int> parents;
  std::vector<double> dist = g.shortestFrom(a, parents);
  EXPECT_NEAR(dist[c], 2.0, 1e-6);
  EXPECT_EQ(HistoryGraph::pathTo(parents, a, c), (std::vector<int>{a, b, c}));
  g.removeEdge(b, c);
  dist = g.shortestFrom(a, parents);
  EXPECT_NEAR(dist[c], 2.0 * std::sqrt(5.0), 1e-5);
  EXPECT_EQ(HistoryGraph::pathTo(parents, a, c), (std::vector<int>{a, d, c}));
  const int lonely = g.addNode({5, 5, 5});
  dist = g.shortestFrom(a, parents);
  EXPECT_TRUE(std::isinf(dist[lonely]));
  EXPECT_TRUE(HistoryGraph::pathTo(parents, a, lonely).empty());
}

/// Everything known, the clearance at a point given by a closed form (a box-shaped free space);
/// the ESDF's gradient is zero (no push: the tests are about the planners' choices).
class KnownSpaceChecker final : public plan::CollisionChecker {
 public:
  using Clearance = float (*)(const Eigen::Vector3f&);
  explicit KnownSpaceChecker(Clearance clearance) : clearance_(clearance) {}
  std::vector<std::uint8_t> spheresFree(const std::vector<Eigen::Vector3f>& centres, float radius_m,
                                        UnknownPolicy) override {
    std::vector<std::uint8_t> out;
    for (const auto& c : centres) out.push_back(clearance_(c) > radius_m ? 1 : 0);
    spheres_tested_ += centres.size();
    return out;
  }
  std::vector<EsdfSample> sample(const std::vector<Eigen::Vector3f>& points) override {
    std::vector<EsdfSample> out;
    for (const auto& p : points) {
      EsdfSample s;
      s.status = EsdfStatus::kKnown;
      s.distance_m = clearance_(p);
      s.gradient = Eigen::Vector3f::Zero();
      out.push_back(s);
    }
    return out;
  }
  float voxelSize() const override { return 0.1f; }
  float maxDistance() const override { return 2.0f; }

 private:
  Clearance clearance_;
};

/// A straight corridor along x (|x| <= 8, |y| <= 1, z in [0.2, 1.8]).
float corridorClearance(const Eigen::Vector3f& p) {
  return std::min({8.0f - std::abs(p.x()), 1.0f - std::abs(p.y()), 0.8f - std::abs(p.z() - 1.0f)});
}

/// Two pockets of unknown space at x = -6 and x = +6: a view within 2 m of a pocket gains 5 m^3
/// until the robot has been within 0.7 m of it.
struct Pockets {
  std::vector<Eigen::Vector3f> centres{{-6.0f, 0.0f, 1.0f}, {6.0f, 0.0f, 1.0f}};
  std::vector<bool> consumed{false, false};
  ViewGainConfig config;

  void visit(const Eigen::Vector3f& p) {
    for (std::size_t i = 0; i < centres.size(); ++i) {
      if ((p - centres[i]).norm() < 0.7f) consumed[i] = true;
    }
  }
  std::vector<ViewGain> gains(const std::vector<Eigen::Vector3f>& positions) const {
    std::vector<ViewGain> out;
    for (const auto& p : positions) {
      float g = 0.0f;
      for (std::size_t i = 0; i < centres.size(); ++i) {
        if (!consumed[i] && (p - centres[i]).norm() < 2.0f) g = 5.0f;
      }
      ViewGain v;
      v.bin_gain_m3.assign(static_cast<std::size_t>(config.yaw_bins), g / 6.0f);
      v.best_gain_m3 = g;
      out.push_back(v);
    }
    return out;
  }
};

ExplorationState corridorState(plan::CollisionChecker& checker, const Pockets& pockets) {
  ExplorationState state;
  state.check_radius_m = 0.35f;
  state.bounds_W =
      Eigen::AlignedBox3f(Eigen::Vector3f(-7.7f, -0.7f, 0.5f), Eigen::Vector3f(7.7f, 0.7f, 1.5f));
  state.checker = &checker;
  state.gain_config = pockets.config;
  state.gain = [&pockets](const std::vector<Eigen::Vector3f>& p) { return pockets.gains(p); };
  return state;
}

struct CorridorRun {
  std::vector<bool> consumed;
  std::set<std::string> modes;
  bool finished = false;
};

/// The history planner from the corridor's middle: its local box (7 m) sees both pockets from
/// there, but from one pocket not the other, so only the cache knows the second one then.
CorridorRun runCorridor(const HistoryConfig& config) {
  KnownSpaceChecker checker(corridorClearance);
  Pockets pockets;
  HistoryPlanner planner(config);
  ExplorationState state = corridorState(checker, pockets);
  state.pose.position_W = Eigen::Vector3f(0.0f, 0.0f, 1.0f);
  CorridorRun run;
  for (int step = 0; step < 60 && !run.finished; ++step) {
    const ExplorationStep s = planner.plan(state);
    run.modes.insert(s.mode);
    run.finished = s.finished;
    for (const Waypoint& w : s.path) {
      // Every flown edge stays in free space.
      EXPECT_TRUE(checker.segmentFree(state.pose.position_W, w.position_W, state.check_radius_m,
                                      UnknownPolicy::kOccupied));
      state.pose = {w.position_W, w.yaw_rad};
      pockets.visit(w.position_W);
    }
  }
  run.consumed = pockets.consumed;
  return run;
}

HistoryConfig corridorConfig() {
  HistoryConfig config;
  config.tree.half_extent_m = Eigen::Vector3f(7.0f, 1.0f, 0.5f);
  config.tree.nodes = 60;
  config.tree.max_batches = 20;
  return config;
}

TEST(HistoryPlanner, ReturnsToACachedViewWhenTheLocalGainIsExhausted) {
  const CorridorRun run = runCorridor(corridorConfig());
  EXPECT_TRUE(run.consumed[0]);
  EXPECT_TRUE(run.consumed[1]);
  EXPECT_TRUE(run.modes.count("global")) << "the second pocket was reached without the cache";
  EXPECT_TRUE(run.finished);
}

TEST(HistoryPlanner, WithoutTheCacheTheFarPocketIsLeft) {
  HistoryConfig config = corridorConfig();
  config.cache_gain_m3 = 1e9f;  // nothing is ever cached
  const CorridorRun run = runCorridor(config);
  EXPECT_NE(run.consumed[0], run.consumed[1]);  // one pocket taken, the other never reached
  EXPECT_FALSE(run.modes.count("global"));
  EXPECT_TRUE(run.finished);
}

/// The corridor, until `pinned`: then no sphere is free (a map that has put a surface inside the
/// check radius of every edge from the robot).
class PinnableChecker final : public plan::CollisionChecker {
 public:
  bool pinned = false;
  std::vector<std::uint8_t> spheresFree(const std::vector<Eigen::Vector3f>& centres, float radius_m,
                                        UnknownPolicy unknown) override {
    if (pinned) return std::vector<std::uint8_t>(centres.size(), 0);
    return corridor_.spheresFree(centres, radius_m, unknown);
  }
  std::vector<EsdfSample> sample(const std::vector<Eigen::Vector3f>& points) override {
    return corridor_.sample(points);
  }
  float voxelSize() const override { return 0.1f; }
  float maxDistance() const override { return 2.0f; }

 private:
  KnownSpaceChecker corridor_{corridorClearance};
};

TEST(HistoryPlanner, WithNoFreeEdgeItHoversOnceThenRetracesItsRoute) {
  PinnableChecker checker;
  Pockets pockets;
  HistoryPlanner planner(corridorConfig());
  ExplorationState state = corridorState(checker, pockets);
  const Eigen::Vector3f start(0.0f, 0.0f, 1.0f);
  state.pose.position_W = start;
  const ExplorationStep first = planner.plan(state);
  ASSERT_EQ(first.mode, "local");
  ASSERT_EQ(first.path.size(), 1u);
  state.pose = {first.path[0].position_W, first.path[0].yaw_rad};
  checker.pinned = true;
  const ExplorationStep hover = planner.plan(state);
  EXPECT_TRUE(hover.path.empty());
  EXPECT_FALSE(hover.finished);
  const ExplorationStep back = planner.plan(state);
  EXPECT_EQ(back.mode, "back");
  ASSERT_EQ(back.path.size(), 1u);
  EXPECT_LT((back.path[0].position_W - start).norm(), 1e-5f);
}

TEST(HistoryPlanner, PinnedAtTheStartItTurnsInPlaceToLookAround) {
  PinnableChecker checker;
  checker.pinned = true;
  Pockets pockets;
  HistoryPlanner planner(corridorConfig());
  ExplorationState state = corridorState(checker, pockets);
  state.pose = {Eigen::Vector3f(0.0f, 0.0f, 1.0f), 0.3f};
  const ExplorationStep hover = planner.plan(state);
  EXPECT_TRUE(hover.path.empty());
  const ExplorationStep turn = planner.plan(state);
  EXPECT_EQ(turn.mode, "turn") << "no route flown yet to retrace";
  ASSERT_EQ(turn.path.size(), 1u);
  EXPECT_LT((turn.path[0].position_W - state.pose.position_W).norm(), 1e-6f) << "in place";
  EXPECT_NEAR(wrapAngle(turn.path[0].yaw_rad - state.pose.yaw_rad), 2.0944f, 1e-4f);
  EXPECT_FALSE(turn.finished);
}

TEST(HistoryPlanner, AGlobalStepFindsViewsBeyondTheTreeBeforeItStops) {
  // A pocket at x = 4 that the tree (box +-1 m in x) never reaches and nothing cached knows:
  // only the global step's samples over the whole bounds find it.
  auto run = [](int global_samples) {
    KnownSpaceChecker checker(corridorClearance);
    Pockets pockets;
    pockets.centres = {{4.0f, 0.0f, 1.0f}};
    pockets.consumed = {false};
    HistoryConfig config = corridorConfig();
    config.tree.half_extent_m = Eigen::Vector3f(1.0f, 1.0f, 0.5f);
    config.global_samples = global_samples;
    config.global_join_radius_m = 5.0f;  // the graph is only the robot's few places here
    HistoryPlanner planner(config);
    ExplorationState state = corridorState(checker, pockets);
    state.pose.position_W = Eigen::Vector3f(-1.0f, 0.0f, 1.0f);
    CorridorRun result;
    for (int step = 0; step < 40 && !result.finished; ++step) {
      const ExplorationStep s = planner.plan(state);
      result.modes.insert(s.mode);
      result.finished = s.finished;
      for (const Waypoint& w : s.path) {
        EXPECT_TRUE(checker.segmentFree(state.pose.position_W, w.position_W,
                                        state.check_radius_m, UnknownPolicy::kOccupied));
        state.pose = {w.position_W, w.yaw_rad};
        pockets.visit(w.position_W);
      }
    }
    result.consumed = pockets.consumed;
    return result;
  };
  const CorridorRun with = run(96);
  EXPECT_TRUE(with.consumed[0]);
  EXPECT_TRUE(with.modes.count("global"));
  EXPECT_TRUE(with.finished) << "and it stops once the pocket is seen";
  const CorridorRun without = run(0);
  EXPECT_FALSE(without.consumed[0]) << "the old stop: no gain in the tree nor the cache";
  EXPECT_TRUE(without.finished);
}

/// A tall hall, |x|, |y| <= 4 m, z in [0, 5] m.
float hallClearance(const Eigen::Vector3f& p) {
  return std::min({4.0f - std::abs(p.x()), 4.0f - std::abs(p.y()), p.z(), 5.0f - p.z()});
}

TEST(HistoryPlanner, ClimbsToTheUnseenTopOfATallHall) {
  // Only views above 3 m gain (the racks' tops); the robot starts at 1.2 m.
  Pockets oracle;
  auto gains = [&oracle](const std::vector<Eigen::Vector3f>& positions) {
    std::vector<ViewGain> out;
    for (const auto& p : positions) {
      ViewGain v;
      const float g = p.z() > 3.0f ? 4.0f : 0.0f;
      v.bin_gain_m3.assign(static_cast<std::size_t>(oracle.config.yaw_bins), g / 6.0f);
      v.best_gain_m3 = g;
      out.push_back(v);
    }
    return out;
  };
  auto highest = [&](float full_height_share) {
    KnownSpaceChecker checker(hallClearance);
    HistoryConfig config;
    config.tree.full_height_share = full_height_share;
    config.global_samples = 0;  // the tree alone
    HistoryPlanner planner(config);
    ExplorationState state;
    state.check_radius_m = 0.4f;
    state.bounds_W = Eigen::AlignedBox3f(Eigen::Vector3f(-3.7f, -3.7f, 0.3f),
                                         Eigen::Vector3f(3.7f, 3.7f, 4.7f));
    state.checker = &checker;
    state.gain_config = oracle.config;
    state.gain = gains;
    state.pose.position_W = Eigen::Vector3f(0.0f, 0.0f, 1.2f);
    float top = state.pose.position_W.z();
    for (int step = 0; step < 6; ++step) {
      const ExplorationStep s = planner.plan(state);
      for (const Waypoint& w : s.path) {
        state.pose = {w.position_W, w.yaw_rad};
        top = std::max(top, w.position_W.z());
      }
    }
    return top;
  };
  // Measured 2026-12-07: the default tree (half its samples over the whole height) flies above
  // 3 m within 6 steps; the box alone (+-0.6 m) never leaves 1.8 m and finds no gain.
  EXPECT_GT(highest(HistoryConfig{}.tree.full_height_share), 3.0f);
  EXPECT_LE(highest(0.0f), 1.2f + 0.6f + 1e-4f);
}

TEST(NbvpPlanner, FliesTheFirstEdgeTowardsGainAndStopsWithoutGain) {
  KnownSpaceChecker checker(corridorClearance);
  Pockets pockets;
  pockets.centres = {{3.0f, 0.0f, 1.0f}};
  pockets.consumed = {false};
  NbvpConfig config;
  NbvpPlanner planner(config);
  ExplorationState state = corridorState(checker, pockets);
  state.pose.position_W = Eigen::Vector3f(0.0f, 0.0f, 1.0f);
  bool finished = false;
  int steps = 0;
  for (; steps < 60 && !finished; ++steps) {
    const ExplorationStep s = planner.plan(state);
    finished = s.finished;
    if (!s.path.empty()) {
      EXPECT_EQ(s.path.size(), 1u);  // receding horizon: one edge per step
      EXPECT_LE((s.path.front().position_W - state.pose.position_W).norm(),
                config.tree.max_edge_m + 1e-4f);
      state.pose = {s.path.front().position_W, s.path.front().yaw_rad};
      pockets.visit(state.pose.position_W);
    }
  }
  EXPECT_TRUE(pockets.consumed[0]);
  EXPECT_TRUE(finished);
}

}  // namespace
// A corridor x in [10, 30], y in [3, 5] off a hall; the robot starts at (9, 4), flies to the
// corridor's end at 1 m/s, then back into the hall.
TEST(DeadEnd, TimesTheEscapeFromTheDeepestPoint) {
  const Eigen::AlignedBox2f corridor(Eigen::Vector2f(10.0f, 3.0f), Eigen::Vector2f(30.0f, 5.0f));
  std::vector<double> times;
  std::vector<Eigen::Vector3f> positions;
  auto fly = [&](float x0, float x1, double t0) {
    const int n = static_cast<int>(std::abs(x1 - x0) * 10.0f);
    for (int i = 0; i <= n; ++i) {
      const float x = x0 + (x1 - x0) * static_cast<float>(i) / static_cast<float>(n);
      times.push_back(t0 + std::abs(x - x0));
      positions.emplace_back(x, 4.0f, 1.2f);
    }
    return t0 + std::abs(x1 - x0);
  };
  const Eigen::Vector3f start(9.0f, 4.0f, 1.2f);
  double t = fly(9.0f, 29.5f, 0.0);  // in at 1 s, deepest at 20.5 s
  const std::vector<double> times_in = times;
  const std::vector<Eigen::Vector3f> positions_in = positions;
  t = fly(29.5f, 8.0f, t + 4.0);  // a 4 s look at the end, then out at 10 - epsilon
  const DeadEndEscape e = analyseDeadEnd(times, positions, deadEndSeenFrom(corridor, start), t);
  ASSERT_TRUE(e.entered);
  EXPECT_NEAR(e.entered_s, 1.0, 0.11);
  EXPECT_NEAR(e.deepest_m, 19.5f, 1e-3f);
  EXPECT_NEAR(e.deepest_s, 20.5, 1e-6);  // the first time at the deepest point
  ASSERT_TRUE(e.left_s.has_value());
  EXPECT_NEAR(*e.left_s, 24.5 + 19.5, 0.11);
  ASSERT_TRUE(e.escape_s.has_value());
  EXPECT_NEAR(*e.escape_s, 4.0 + 19.5, 0.11);

  // Still inside when the run ends: no escape, the time after the deepest point as a bound.
  const DeadEndEscape stuck =
      analyseDeadEnd(times_in, positions_in, deadEndSeenFrom(corridor, start), 100.0);
  EXPECT_FALSE(stuck.left_s.has_value());
  EXPECT_FALSE(stuck.escape_s.has_value());
  EXPECT_NEAR(stuck.after_deepest_s, 100.0 - 20.5, 1e-6);
  // Never entered.
  EXPECT_FALSE(analyseDeadEnd({0.0}, {start}, deadEndSeenFrom(corridor, start), 1.0).entered);
  EXPECT_THROW(analyseDeadEnd({0.0, 1.0}, {start}, deadEndSeenFrom(corridor, start), 1.0),
               InputError);
  EXPECT_THROW(analyseDeadEnd({0.0}, {start}, DeadEnd{}, 1.0), InputError);  // empty region

  // A start inside the dead end: depth counts from the given mouth, not from the start.
  const DeadEnd opening_west{corridor, Eigen::Vector2f(10.0f, 4.0f)};
  times.clear();
  positions.clear();
  t = fly(20.0f, 29.0f, 0.0);  // deepest (19 m from the mouth) at 9 s
  t = fly(29.0f, 9.0f, t);     // out at x < 10: 19 s later
  const DeadEndEscape inside = analyseDeadEnd(times, positions, opening_west, t);
  ASSERT_TRUE(inside.entered);
  EXPECT_NEAR(inside.entered_s, 0.0, 1e-9);
  EXPECT_NEAR(inside.deepest_m, 19.0f, 1e-3f);
  EXPECT_NEAR(inside.deepest_s, 9.0, 1e-6);
  ASSERT_TRUE(inside.escape_s.has_value());
  EXPECT_NEAR(*inside.escape_s, 19.0, 0.11);
}

}  // namespace strata::explore
