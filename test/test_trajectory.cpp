// Trajectories along polylines: limits from the samples, rest at the ends, clearance against the
// analytic geometry, and the corner deviation shrinking next to an obstacle.
#include <gtest/gtest.h>

#include <cmath>

#include "strata/core/error.h"
#include "strata/plan/collision_checker.h"
#include "strata/plan/flight_trajectory.h"
#include "plan_test_scene.h"

namespace strata::plan {
namespace {

using test::RoomScene;

constexpr float kVMax = 1.0f;
constexpr float kAMax = 0.8f;

TrajectoryLimits limits() {
  TrajectoryLimits l;
  l.v_max_mps = kVMax;
  l.a_max_mps2 = kAMax;
  return l;
}

/// Largest tangential and normal acceleration from finite differences of the sampled velocities.
void finiteDifferenceAcceleration(const Trajectory& t, float* tangential, float* normal) {
  *tangential = *normal = 0.0f;
  for (std::size_t k = 1; k < t.samples.size(); ++k) {
    const TrajectorySample& a = t.samples[k - 1];
    const TrajectorySample& b = t.samples[k];
    const auto dt = static_cast<float>(b.t_s - a.t_s);
    ASSERT_GT(dt, 0.0f) << k;
    const Eigen::Vector3f acc = (b.v_W - a.v_W) / dt;
    const Eigen::Vector3f dir = b.p_W - a.p_W;
    const Eigen::Vector3f u = dir.normalized();
    *tangential = std::max(*tangential, std::fabs(acc.dot(u)));
    *normal = std::max(*normal, (acc - u * acc.dot(u)).norm());
  }
}

/// Smallest analytic distance along the chords between samples.
float sampledClearance(const Trajectory& t, const test::Sdf& sdf) {
  float d = std::numeric_limits<float>::infinity();
  for (std::size_t k = 1; k < t.samples.size(); ++k) {
    d = std::min(d, test::segmentDistance(sdf, t.samples[k - 1].p_W, t.samples[k].p_W));
  }
  return d;
}

TEST(Trajectory, ThroughTheDoorWithinTheLimitsAndTheClearance) {
  const RoomScene& room = test::roomScene(true);
  HostCollisionChecker checker(room.map.esdf);
  const float radius = 0.25f;
  const std::vector<Eigen::Vector3f> path{
      {-2.0f, -1.2f, 0.8f}, {-0.4f, 1.0f, 0.8f}, {0.4f, 1.0f, 0.8f}, {2.0f, -1.2f, 0.8f}};
  ASSERT_TRUE(checker.pathFree(path, radius, UnknownPolicy::kOccupied));
  const Trajectory t = makeTrajectory(path, limits(), checker, radius, UnknownPolicy::kOccupied);
  ASSERT_GT(t.samples.size(), 50u);
  EXPECT_TRUE(t.collision_free);
  // Ends: at the path's ends, at rest.
  EXPECT_EQ(t.samples.front().p_W, path.front());
  EXPECT_EQ(t.samples.back().p_W, path.back());
  EXPECT_EQ(t.samples.front().v_W.norm(), 0.0f);
  EXPECT_EQ(t.samples.back().v_W.norm(), 0.0f);
  EXPECT_EQ(t.samples.front().t_s, 0.0);
  EXPECT_DOUBLE_EQ(t.samples.back().t_s, t.duration_s);
  // Limits, from the samples.
  float speed = 0.0f;
  for (const TrajectorySample& s : t.samples) speed = std::max(speed, s.v_W.norm());
  EXPECT_LE(speed, kVMax + 1e-5f);
  EXPECT_GT(speed, 0.9f * kVMax);  // long legs reach the limit
  EXPECT_FLOAT_EQ(speed, t.max_speed_mps);
  float tangential = 0.0f, normal = 0.0f;
  finiteDifferenceAcceleration(t, &tangential, &normal);
  EXPECT_LE(tangential, kAMax * 1.02f);
  EXPECT_LE(normal, kAMax * 1.1f);
  EXPECT_GT(normal, 0.3f * kAMax);  // the corners are taken at speed, not stopped at
  for (const TrajectorySample& s : t.samples) {
    const Eigen::Vector3f u = s.v_W.norm() > 0.0f ? s.v_W.normalized() : Eigen::Vector3f::Zero();
    EXPECT_LE((s.a_W - u * s.a_W.dot(u)).norm(), kAMax * 1.001f);
  }
  // Clearance against the true walls.
  EXPECT_GE(sampledClearance(t, [&](const Eigen::Vector3f& p) { return room.distance(p); }),
            radius);
  // Rounded corners: the robot never passes through the interior vertices.
  ASSERT_EQ(t.corner_deviation_m.size(), 2u);
  for (const float deviation : t.corner_deviation_m) EXPECT_GT(deviation, 0.05f);
  // Interpolation.
  EXPECT_EQ(t.at(-1.0).p_W, path.front());
  EXPECT_EQ(t.at(t.duration_s + 1.0).p_W, path.back());
  const TrajectorySample& mid = t.samples[t.samples.size() / 2];
  EXPECT_LT((t.at(mid.t_s).p_W - mid.p_W).norm(), 1e-5f);
  const TrajectorySample& next = t.samples[t.samples.size() / 2 + 1];
  const Eigen::Vector3f half = t.at(0.5 * (mid.t_s + next.t_s)).p_W;
  EXPECT_LT((half - 0.5f * (mid.p_W + next.p_W)).norm(), 1e-5f);
}

/// A 60 degree turn at `corner` with 4 m legs, in a box of free space (blocks -6..5, 0..1), with
/// or without a ball on the inner side of the bend.
struct Bend {
  Eigen::Vector3f corner{0.5f, -2.5f, 0.8f};
  Eigen::Vector3f u_in{1.0f, 0.0f, 0.0f};
  Eigen::Vector3f u_out{0.5f, std::sqrt(3.0f) / 2.0f, 0.0f};
  std::vector<Eigen::Vector3f> path() const {
    return {corner - 4.0f * u_in, corner, corner + 4.0f * u_out};
  }
  test::Ball ball() const { return {corner + 0.8f * (u_out - u_in).normalized(), 0.2f}; }
};

TEST(Trajectory, TheCornerDeviationShrinksNextToAnObstacle) {
  const Bend bend;
  const float radius = 0.2f;
  const std::vector<test::Ball> balls{bend.ball()};
  const auto with_ball = [&](const Eigen::Vector3f& p) {
    return test::sceneDistance(p, {}, balls);
  };
  const auto free_space = [](const Eigen::Vector3f&) { return 5.0f; };
  const test::AnalyticMap open =
      test::makeAnalyticMap(free_space, {-6, -6, 0}, {5, 5, 1}, 0.1f, 1.5f);
  const test::AnalyticMap blocked =
      test::makeAnalyticMap(with_ball, {-6, -6, 0}, {5, 5, 1}, 0.1f, 1.5f);
  HostCollisionChecker open_checker(open.esdf);
  HostCollisionChecker blocked_checker(blocked.esdf);
  ASSERT_TRUE(blocked_checker.pathFree(bend.path(), radius, UnknownPolicy::kOccupied));
  const Trajectory wide =
      makeTrajectory(bend.path(), limits(), open_checker, radius, UnknownPolicy::kOccupied);
  const Trajectory tight =
      makeTrajectory(bend.path(), limits(), blocked_checker, radius, UnknownPolicy::kOccupied);
  ASSERT_EQ(wide.corner_deviation_m.size(), 1u);
  ASSERT_EQ(tight.corner_deviation_m.size(), 1u);
  EXPECT_TRUE(wide.collision_free);
  EXPECT_TRUE(tight.collision_free);
  EXPECT_GT(tight.corner_deviation_m[0], 0.0f);
  EXPECT_LT(tight.corner_deviation_m[0], wide.corner_deviation_m[0] - 0.05f);
  // The margin at the vertex allowed more; the samples' capsule check (conservative by up to a
  // few voxels) refused that curve and halved it: the retry path ran.
  const EsdfSample at_corner = blocked_checker.sample({bend.corner})[0];
  EXPECT_LE(tight.corner_deviation_m[0], 0.5f * (at_corner.distance_m - radius) + 1e-4f);
  // The deviation reported is the distance from the vertex to the sampled curve.
  float nearest = std::numeric_limits<float>::infinity();
  for (const TrajectorySample& s : tight.samples)
    nearest = std::min(nearest, (s.p_W - bend.corner).norm());
  EXPECT_NEAR(nearest, tight.corner_deviation_m[0], 0.02f);
  EXPECT_GE(sampledClearance(tight, with_ball), radius);
  // The same rounding in free space would have cut into the ball's clearance.
  EXPECT_LT(sampledClearance(wide, with_ball), radius);
}

TEST(Trajectory, ASharpCornerIsAStop) {
  const Bend bend;
  const auto free_space = [](const Eigen::Vector3f&) { return 5.0f; };
  const test::AnalyticMap open =
      test::makeAnalyticMap(free_space, {-6, -6, 0}, {5, 5, 1}, 0.1f, 1.5f);
  HostCollisionChecker checker(open.esdf);
  // Radius 1.45 m: the ESDF's 1.5 m reach leaves no margin to round the corner with.
  const Trajectory t = makeTrajectory(bend.path(), limits(), checker, 1.45f, UnknownPolicy::kFree);
  ASSERT_EQ(t.corner_deviation_m.size(), 1u);
  EXPECT_EQ(t.corner_deviation_m[0], 0.0f);
  bool stopped_at_corner = false;
  for (const TrajectorySample& s : t.samples) {
    if ((s.p_W - bend.corner).norm() < 1e-5f) stopped_at_corner = s.v_W.norm() == 0.0f;
  }
  EXPECT_TRUE(stopped_at_corner);
}

TEST(Trajectory, OnePointAndBadInput) {
  const test::AnalyticMap open = test::makeAnalyticMap([](const Eigen::Vector3f&) { return 5.0f; },
                                                       {0, 0, 0}, {0, 0, 0}, 0.1f, 1.0f);
  HostCollisionChecker checker(open.esdf);
  const Eigen::Vector3f p(0.4f, 0.4f, 0.4f);
  const Trajectory t = makeTrajectory({p, p}, limits(), checker, 0.1f, UnknownPolicy::kOccupied);
  ASSERT_EQ(t.samples.size(), 1u);
  EXPECT_EQ(t.duration_s, 0.0);
  EXPECT_EQ(t.at(3.0).p_W, p);
  EXPECT_THROW(makeTrajectory({}, limits(), checker, 0.1f, UnknownPolicy::kOccupied), InputError);
  TrajectoryLimits bad = limits();
  bad.a_max_mps2 = 0.0f;
  EXPECT_THROW(makeTrajectory({p}, bad, checker, 0.1f, UnknownPolicy::kOccupied), InputError);
  EXPECT_THROW(makeTrajectory({p, Eigen::Vector3f::Constant(NAN)}, limits(), checker, 0.1f,
                              UnknownPolicy::kOccupied),
               InputError);
}

}  // namespace
}  // namespace strata::plan
