#pragma once
// Synthetic multi-session pose graphs with known truth, shared by test_pose_graph and
// `strata-bench posegraph`: sessions driving overlapping circles (common centre area, each
// revisiting its start), each recorded in its own frame S (origin near its first camera, random
// yaw), odometry drifting by a random walk per edge, and true loops with small noise between
// keyframes near each other, across and within sessions. Same config, same graph. Thread safety:
// free functions.
#include <Eigen/Geometry>
#include <cstdint>
#include <vector>

#include "strata/align/pose_graph.h"

namespace strata::align {

struct SyntheticGraphConfig {
  int sessions = 5;
  int keyframes_per_session = 60;
  double radius_m = 3.0;         // circle radius
  double centre_offset_m = 0.2;  // circle centres on a ring of this radius
  double laps = 1.15;            // > 1: the end of a session revisits its start
  /// Odometry error per edge (per axis): the random walk that makes the drift.
  double odometry_sigma_m = 0.001;
  double odometry_sigma_rad = 0.001;
  /// Loop measurement error (per axis).
  double loop_sigma_m = 0.002;
  double loop_sigma_rad = 0.001;
  /// The information matrices claim sigmas this many times the true ones (odometry and loops
  /// alike, so their relative weights are right): a verifier's conservative bound. 0 leaves the
  /// odometry information empty (the graph's default) and gives loops 1e4 (1 cm, 0.01 rad).
  double information_inflation = 5.0;
  double loop_distance_m = 0.5;    // keyframes nearer than this (and facing alike) may be joined
  int loop_every = 4;              // one loop per this many keyframes of a, per session pair
  int intra_session_min_gap = 20;  // keyframes apart for a loop within a session
  std::uint64_t seed = 1;
};

struct SyntheticGraph {
  std::vector<GraphSession> sessions;  // T_S_C from drifted odometry
  std::vector<GraphLoop> loops;        // true loops
  std::vector<std::vector<Eigen::Isometry3d>> T_W_C_true;
  std::vector<Eigen::Isometry3d> T_W_S_true;  // session 0: identity
};

SyntheticGraph makeSyntheticGraph(const SyntheticGraphConfig& config);

/// Appends `count` false loops between random keyframes of different places (true distance over
/// 2 m) with a random T_a_b (up to 1 m and 0.5 rad): the kind a place recogniser confuses.
void addRandomFalseLoops(SyntheticGraph& graph, int count, std::uint64_t seed);

/// Appends `count` false loops from session `session` to other sessions that all agree on the
/// wrong placement T_W_S_true[session] * T_wrong: the trap a naive average would fall into.
void addAgreeingFalseLoops(SyntheticGraph& graph, std::size_t session, int count,
                           const Eigen::Isometry3d& T_wrong, std::uint64_t seed);

/// Each keyframe's odometry placed by the session's true frame: T_W_S_true * T_S_C.
std::vector<std::vector<Eigen::Isometry3d>> odometryInTrueFrame(const SyntheticGraph& graph);

/// RMS of |t(T_W_C) - t(T_W_C_true)| over the keyframes of the sessions with a non-empty
/// estimate (no alignment: both share the world frame of session 0).
double translationRmse(const std::vector<std::vector<Eigen::Isometry3d>>& T_W_C,
                       const SyntheticGraph& graph);

}  // namespace strata::align
