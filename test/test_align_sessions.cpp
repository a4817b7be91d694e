// Multi-session alignment end to end on simulated sessions in their own drifting frames: every
// session registered, the result scored against the simulator's truth, loops checked against it,
// a session that shares no place with the others left unaligned, bad input refused.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "strata/align/alignment_eval.h"
#include "strata/align/session_alignment.h"
#include "strata/core/error.h"
#include "strata/sim/session/sim_session.h"
#include "strata/sim/world/world_paths.h"

namespace strata::align {
namespace {

std::shared_ptr<const sim::World> loadShipped(const std::string& name) {
  return std::make_shared<const sim::World>(sim::World::load(sim::findWorld(name)));
}

/// A session of `world` with drifting odometry moved into a frame of its own (yaw and
/// translation, as gravity-aligned odometry frames differ).
struct OwnFrameSession {
  std::unique_ptr<sim::SimSessionDataset> dataset;
  Eigen::Isometry3d T_S_W = Eigen::Isometry3d::Identity();
};

OwnFrameSession makeSession(const std::shared_ptr<const sim::World>& world, int session,
                            int frames, std::uint32_t offset_seed) {
  sim::SimSessionConfig config;
  config.max_frames = frames;
  config.drift = true;
  OwnFrameSession out;
  out.dataset = std::make_unique<sim::SimSessionDataset>(world, session, config);
  std::mt19937 rng(offset_seed);
  std::uniform_real_distribution<double> yaw(-M_PI, M_PI), xy(-5.0, 5.0), z(-0.5, 0.5);
  out.T_S_W.linear() = Eigen::AngleAxisd(yaw(rng), Eigen::Vector3d::UnitZ()).toRotationMatrix();
  out.T_S_W.translation() = Eigen::Vector3d(xy(rng), xy(rng), z(rng));
  std::vector<std::optional<Eigen::Isometry3d>> own;
  for (const Eigen::Isometry3d& T_W_C : out.dataset->givenPoses()) own.push_back(out.T_S_W * T_W_C);
  out.dataset->replaceGivenPoses(own);
  return out;
}

SessionTruth truthOf(const sim::SimSessionDataset& d) {
  SessionTruth truth;
  for (const Eigen::Isometry3d& T : d.truePoses()) truth.push_back(T);
  return truth;
}

TEST(AlignSessions, RoomSessionsInTheirOwnDriftingFramesAreRegistered) {
  const auto world = loadShipped("room");
  std::vector<OwnFrameSession> sessions;
  std::vector<AlignSession> inputs;
  std::vector<SessionTruth> truth;
  for (int s = 0; s < 3; ++s) sessions.push_back(makeSession(world, s, 40, 100 + s));
  for (const OwnFrameSession& s : sessions) {
    inputs.push_back(sessionFromDataset(*s.dataset));
    truth.push_back(truthOf(*s.dataset));
  }
  AlignConfig config;
  const AlignResult result = alignSessions(inputs, config);
  const AlignmentScore score = scoreAlignment(result, truth, config);
  std::printf("room, 3 sessions x 40 frames: %s\n", alignmentScoreJson(score).c_str());
  for (std::size_t s = 0; s < sessions.size(); ++s) EXPECT_TRUE(result.sessions[s].aligned) << s;
  EXPECT_GT(score.ate_before_rmse_m, 0.5);  // the frames are metres apart before
  EXPECT_LT(score.ate_after_rmse_m, 0.02);
  EXPECT_EQ(score.accepted_false, 0u);
  EXPECT_GT(score.accepted_true, 10u);
  // Keyframe-level recall against a generous notion of overlap (within 1 m and 30 degrees); the
  // room's plain walls leave many such pairs without enough ORB matches.
  EXPECT_GT(score.loop_recall, 0.3);
  for (std::size_t s = 1; s < sessions.size(); ++s) {
    EXPECT_LT(score.sessions[s].T_W_S_error_m, 0.03) << s;
    EXPECT_LT(score.sessions[s].T_W_S_error_deg, 1.0) << s;
  }
  // Every frame follows its keyframes: the aligned frames are the corrected odometry.
  EXPECT_EQ(result.sessions[1].frame_T_W_C.size(), sessions[1].dataset->size());
}

TEST(AlignSessions, ASessionOfAnotherWorldStaysUnalignedAndTheOthersAlign) {
  const auto room = loadShipped("room");
  const auto warehouse = loadShipped("warehouse");
  std::vector<OwnFrameSession> sessions;
  sessions.push_back(makeSession(room, 0, 30, 7));
  sessions.push_back(makeSession(warehouse, 0, 30, 8));
  sessions.push_back(makeSession(room, 1, 30, 9));
  std::vector<AlignSession> inputs;
  for (const OwnFrameSession& s : sessions) inputs.push_back(sessionFromDataset(*s.dataset));
  const AlignResult result = alignSessions(inputs);
  EXPECT_TRUE(result.sessions[0].aligned);
  EXPECT_FALSE(result.sessions[1].aligned);
  EXPECT_TRUE(result.sessions[1].frame_T_W_C.empty());
  EXPECT_TRUE(result.sessions[2].aligned);
  for (const AlignLoop& loop : result.loops) {
    if (loop.session_a == 1 || loop.session_b == 1) {
      EXPECT_FALSE(loop.accepted);
    }
  }
}

TEST(AlignSessions, BadInputIsRefusedNamingTheSession) {
  const auto world = loadShipped("room");
  const OwnFrameSession session = makeSession(world, 0, 5, 1);
  AlignSession input = sessionFromDataset(*session.dataset);
  EXPECT_THROW(alignSessions({}), InputError);
  AlignSession no_keyframes = input;
  no_keyframes.keyframes.clear();
  try {
    alignSessions({no_keyframes});
    FAIL() << "no keyframes accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("no keyframes"), std::string::npos) << e.what();
  }
  AlignSession short_poses = input;
  short_poses.frame_T_S_C.pop_back();
  EXPECT_THROW(alignSessions({short_poses}), InputError);
  AlignSession nan_pose = input;
  nan_pose.frame_T_S_C[2].translation().x() = NAN;
  EXPECT_THROW(alignSessions({nan_pose}), InputError);
  AlignSession unordered = input;
  std::swap(unordered.keyframes[1], unordered.keyframes[2]);
  EXPECT_THROW(alignSessions({unordered}), InputError);
}

}  // namespace
}  // namespace strata::align
