// Multi-session pose graph (align/pose_graph.h) on synthetic sessions with known truth
// (align/synthetic_sessions.h): drift removed, sessions placed, false loops switched off,
// sessions without enough loops left unaligned, bad input refused with an error naming it.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>

#include "strata/align/pose_graph.h"
#include "strata/align/synthetic_sessions.h"
#include "strata/core/error.h"

namespace strata::align {
namespace {

using Eigen::Isometry3d;

constexpr double kDegree = 3.14159265358979323846 / 180.0;

double rotationAngle(const Isometry3d& x, const Isometry3d& y) {
  return Eigen::AngleAxisd(x.linear().transpose() * y.linear()).angle();
}

void expectSessionsPlaced(const PoseGraphResult& result, const SyntheticGraph& graph,
                          const std::vector<std::size_t>& sessions) {
  for (std::size_t s : sessions) {
    ASSERT_TRUE(result.T_W_S[s].has_value()) << "session " << s << " unaligned";
    const Isometry3d& T_W_S = *result.T_W_S[s];
    EXPECT_LT((T_W_S.translation() - graph.T_W_S_true[s].translation()).norm(), 0.01)
        << "session " << s;
    EXPECT_LT(rotationAngle(T_W_S, graph.T_W_S_true[s]), 0.5 * kDegree) << "session " << s;
    EXPECT_EQ(result.T_W_C[s].size(), graph.sessions[s].T_S_C.size());
  }
}

std::size_t countAccepted(const PoseGraphResult& result, std::size_t from, std::size_t to) {
  std::size_t accepted = 0;
  for (std::size_t l = from; l < to; ++l) accepted += result.loop_accepted[l] ? 1 : 0;
  return accepted;
}

TEST(PoseGraph, AlignsSessionsAndRemovesTheDrift) {
  const SyntheticGraph graph = makeSyntheticGraph(SyntheticGraphConfig{});
  ASSERT_GE(graph.loops.size(), 60u);
  const double ate_before = translationRmse(odometryInTrueFrame(graph), graph);
  const PoseGraphResult result = optimisePoseGraph(graph.sessions, graph.loops);
  const double ate_after = translationRmse(result.T_W_C, graph);
  std::printf("ATE %.4f m -> %.4f m, %d iterations, %.3f s\n%s\n", ate_before, ate_after,
              result.iterations, result.solve_seconds, result.report.c_str());
  EXPECT_GT(ate_before, 0.03);
  EXPECT_LT(ate_after, 0.01);
  expectSessionsPlaced(result, graph, {0, 1, 2, 3, 4});
  EXPECT_TRUE(result.T_W_S[0]->isApprox(Isometry3d::Identity(), 1e-12));
  EXPECT_GE(countAccepted(result, 0, graph.loops.size()), graph.loops.size() * 95 / 100);
  EXPECT_LT(result.final_cost, result.initial_cost);
}

// RMS translation error of the relative poses the true loops measure (the revisits).
double revisitError(const std::vector<std::vector<Isometry3d>>& T_W_C,
                    const SyntheticGraph& graph) {
  double sum = 0.0;
  for (const GraphLoop& loop : graph.loops) {
    const Isometry3d estimate =
        T_W_C[loop.session_a][loop.keyframe_a].inverse() * T_W_C[loop.session_b][loop.keyframe_b];
    const Isometry3d truth = graph.T_W_C_true[loop.session_a][loop.keyframe_a].inverse() *
                             graph.T_W_C_true[loop.session_b][loop.keyframe_b];
    sum += (estimate.translation() - truth.translation()).squaredNorm();
  }
  return std::sqrt(sum / static_cast<double>(graph.loops.size()));
}

// One session, two laps: its loops cannot undo the drift of the first lap (nothing outside the
// session measures it), but they make the second lap meet the first.
TEST(PoseGraph, IntraSessionLoopsCloseASingleSession) {
  SyntheticGraphConfig config;
  config.sessions = 1;
  config.laps = 2.0;
  config.keyframes_per_session = 100;
  const SyntheticGraph graph = makeSyntheticGraph(config);
  ASSERT_GE(graph.loops.size(), 10u);
  const double before = revisitError(odometryInTrueFrame(graph), graph);
  const PoseGraphResult result = optimisePoseGraph(graph.sessions, graph.loops);
  const double after = revisitError(result.T_W_C, graph);
  std::printf("revisit error %.4f m -> %.4f m\n", before, after);
  EXPECT_GT(before, 0.03);
  EXPECT_LT(after, 0.005);
  EXPECT_GE(countAccepted(result, 0, graph.loops.size()), graph.loops.size() * 9 / 10);
}

TEST(PoseGraph, SwitchesOffFalseLoopsAndOutVotesAgreeingOnes) {
  SyntheticGraph graph = makeSyntheticGraph(SyntheticGraphConfig{});
  const std::size_t true_loops = graph.loops.size();
  // Four false loops agreeing on a placement of session 2 rotated 30 degrees and shifted 1.5 m.
  const Isometry3d T_wrong = Eigen::Translation3d(1.5, -0.5, 0.2) *
                             Eigen::AngleAxisd(30.0 * kDegree, Eigen::Vector3d::UnitZ());
  addAgreeingFalseLoops(graph, 2, 4, T_wrong, 7);
  // The rest of ~20 % false loops at random.
  addRandomFalseLoops(graph, static_cast<int>(true_loops / 4) - 4, 11);
  const double ate_before = translationRmse(odometryInTrueFrame(graph), graph);
  const PoseGraphResult result = optimisePoseGraph(graph.sessions, graph.loops);
  const double ate_after = translationRmse(result.T_W_C, graph);
  std::printf("%zu true + %zu false loops: ATE %.4f m -> %.4f m\n", true_loops,
              graph.loops.size() - true_loops, ate_before, ate_after);
  EXPECT_EQ(countAccepted(result, true_loops, graph.loops.size()), 0u);
  for (std::size_t l = true_loops; l < graph.loops.size(); ++l) {
    EXPECT_LT(result.loop_switch[l], 0.1) << "false loop " << l;
  }
  EXPECT_GE(countAccepted(result, 0, true_loops), true_loops * 95 / 100);
  EXPECT_LT(ate_after, 0.01);
  expectSessionsPlaced(result, graph, {0, 1, 2, 3, 4});
}

TEST(PoseGraph, LeavesSessionsWithoutEnoughLoopsUnaligned) {
  SyntheticGraph graph = makeSyntheticGraph(SyntheticGraphConfig{});
  // Session 3 keeps no loop, session 4 one loop to session 0 (min_consensus_loops is 2).
  std::vector<GraphLoop> loops;
  const GraphLoop* single = nullptr;
  for (const GraphLoop& loop : graph.loops) {
    const bool touches_3 = loop.session_a == 3 || loop.session_b == 3;
    const bool touches_4 = loop.session_a == 4 || loop.session_b == 4;
    if (!touches_3 && !touches_4) loops.push_back(loop);
    if (!single && loop.session_a == 0 && loop.session_b == 4) single = &loop;
  }
  ASSERT_NE(single, nullptr);
  loops.push_back(*single);
  const PoseGraphResult result = optimisePoseGraph(graph.sessions, loops);
  EXPECT_FALSE(result.T_W_S[3].has_value());
  EXPECT_FALSE(result.T_W_S[4].has_value());
  EXPECT_TRUE(result.T_W_C[3].empty());
  EXPECT_TRUE(result.T_W_C[4].empty());
  EXPECT_FALSE(result.loop_accepted.back());
  EXPECT_EQ(result.loop_switch.back(), 0.0);
  expectSessionsPlaced(result, graph, {0, 1, 2});
  EXPECT_LT(translationRmse(result.T_W_C, graph), 0.01);
}

std::string inputErrorOf(const std::vector<GraphSession>& sessions,
                         const std::vector<GraphLoop>& loops) {
  try {
    optimisePoseGraph(sessions, loops);
  } catch (const InputError& e) {
    return e.what();
  }
  return "no InputError";
}

void expectMentions(const std::string& message, const std::string& part) {
  EXPECT_NE(message.find(part), std::string::npos) << "'" << message << "' lacks '" << part << "'";
}

TEST(PoseGraph, RefusesBadInputNamingIt) {
  SyntheticGraphConfig config;
  config.sessions = 2;
  config.keyframes_per_session = 30;
  const SyntheticGraph graph = makeSyntheticGraph(config);
  ASSERT_GE(graph.loops.size(), 2u);

  std::vector<GraphLoop> loops = graph.loops;
  loops[1].session_b = 5;
  expectMentions(inputErrorOf(graph.sessions, loops), "loop 1: session_b 5 does not exist");
  loops = graph.loops;
  loops[0].keyframe_a = 30;
  expectMentions(inputErrorOf(graph.sessions, loops), "loop 0: keyframe_a 30 does not exist");
  loops = graph.loops;
  loops[1].T_a_b.translation().x() = std::numeric_limits<double>::quiet_NaN();
  expectMentions(inputErrorOf(graph.sessions, loops), "loop 1: T_a_b");
  loops = graph.loops;
  loops[0].information(2, 2) = -1.0;
  expectMentions(inputErrorOf(graph.sessions, loops), "loop 0 information");

  std::vector<GraphSession> sessions = graph.sessions;
  sessions[1].T_S_C.clear();
  expectMentions(inputErrorOf(sessions, {}), "session 1 has no keyframes");
  sessions = graph.sessions;
  sessions[0].odometry_information.assign(5, store::Matrix6d::Identity());
  expectMentions(inputErrorOf(sessions, {}), "session 0: 5 odometry information matrices for 29");
  sessions = graph.sessions;
  sessions[1].T_S_C[7].translation().z() = std::numeric_limits<double>::quiet_NaN();
  expectMentions(inputErrorOf(sessions, {}), "session 1 keyframe 7: T_S_C");
  expectMentions(inputErrorOf({}, {}), "no sessions");

  PoseGraphConfig bad;
  bad.switch_prior_weight = 0.0;
  EXPECT_THROW(bad.validate(), InputError);
}

}  // namespace
}  // namespace strata::align
