#pragma once
// Multi-session pose graph (Ceres): every session's keyframes in its own odometry frame S,
// odometry edges between consecutive keyframes, loop edges within and across sessions. The first
// session anchors the world frame (T_W_S0 = identity); another session is placed by the loops
// joining it to sessions already placed (consensus of their implied T_W_S), then all placed
// sessions are relaxed together. Loops carry switchable constraints (Sünderhauf & Protzel 2012):
// a switch variable in [0, 1] scales each loop residual, with a prior pulling it to 1, so a false
// loop that disagrees with the rest is switched off instead of bending the map. A session that no
// loop joins to the anchor's component stays unaligned (reported, not forced into place).
// Frames: T_S_C camera-to-session (odometry), T_W_C camera-to-world, T_a_b = T_X_a^-1 * T_X_b.
// Information matrices in (tx ty tz rx ry rz) order of a right perturbation T * Exp(delta).
// Thread safety: free function; Ceres uses `threads` threads.
#include <Eigen/Geometry>
#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "strata/store/store_types.h"

namespace strata::align {

struct GraphSession {
  std::vector<Eigen::Isometry3d> T_S_C;           // keyframes in time order
  /// Information of the odometry edge k -> k+1 (size T_S_C.size() - 1), or empty: every edge
  /// gets PoseGraphConfig::default_odometry_information.
  std::vector<store::Matrix6d> odometry_information;
};

struct GraphLoop {
  std::size_t session_a = 0, keyframe_a = 0;
  std::size_t session_b = 0, keyframe_b = 0;
  Eigen::Isometry3d T_a_b = Eigen::Isometry3d::Identity();  // camera b in camera a
  store::Matrix6d information = store::Matrix6d::Identity();
};

struct PoseGraphConfig {
  store::Matrix6d default_odometry_information = store::Matrix6d::Identity() * 1e4;
  /// Information of the switch prior (1 - s)^2. A loop ends at s = w / (w + chi2), so with
  /// switch_accept 0.5 it is kept while its chi2 stays under w: 16.8 is the 99 % point of chi2
  /// with 6 degrees of freedom, so a true loop whose information states its noise is kept.
  double switch_prior_weight = 16.8;
  double switch_accept = 0.5;         // a loop whose switch ends above this is kept
  /// Placing a session: a loop's implied T_W_S agrees with the consensus within these.
  double consensus_translation_m = 0.3;
  double consensus_rotation_rad = 0.15;
  int min_consensus_loops = 2;        // loops agreeing on a session's placement to place it
  int max_iterations = 100;
  int threads = 2;
  void validate() const;
};

struct PoseGraphResult {
  std::vector<std::optional<Eigen::Isometry3d>> T_W_S;  // per session; nullopt: unaligned
  /// Per session, per keyframe: optimised T_W_C (empty for an unaligned session).
  std::vector<std::vector<Eigen::Isometry3d>> T_W_C;
  std::vector<double> loop_switch;  // per input loop: final switch in [0, 1] (0: not used)
  std::vector<bool> loop_accepted;  // switch above switch_accept and both sessions aligned
  int iterations = 0;
  double initial_cost = 0.0, final_cost = 0.0;
  double solve_seconds = 0.0;       // wall time of placement and relaxation
  std::string report;               // Ceres's brief report
};

/// Aligns and relaxes the sessions. InputError for a loop naming a session or keyframe that does
/// not exist, a session without keyframes, a wrong odometry_information count or non-finite
/// input.
PoseGraphResult optimisePoseGraph(const std::vector<GraphSession>& sessions,
                                  const std::vector<GraphLoop>& loops,
                                  const PoseGraphConfig& config = {});

}  // namespace strata::align
