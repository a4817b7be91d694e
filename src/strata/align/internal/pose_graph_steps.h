#pragma once
// The steps of optimisePoseGraph (pose_graph.cpp), apart so each reads on its own: input checks,
// placement of the sessions by loop consensus, relaxation of the placed sessions in Ceres.
// Internal to strata::align.
#include <Eigen/Geometry>
#include <optional>
#include <vector>

#include "strata/align/pose_graph.h"

namespace strata::align::internal {

/// InputError naming the first bad session, keyframe, loop or information matrix.
void checkPoseGraphInput(const std::vector<GraphSession>& sessions,
                         const std::vector<GraphLoop>& loops);

/// Initial estimate: session 0 at the identity, every other session placed by the consensus of
/// its loops to sessions placed before it (nullopt where no consensus is reached). A loop starts
/// switched on when the pose it implies for session b's first keyframe agrees with b's placement
/// within the consensus thresholds; loops touching an unplaced session are off.
struct Placement {
  std::vector<std::optional<Eigen::Isometry3d>> T_W_S;
  std::vector<double>
      initial_switch;          // per loop: 1 (on) or 0 (starts off; the solve may turn it on)
  std::vector<bool> in_solve;  // per loop: both sessions placed, so in the solve
};
Placement placeSessions(const std::vector<GraphSession>& sessions,
                        const std::vector<GraphLoop>& loops, const PoseGraphConfig& config);

/// Relaxes every placed session (odometry edges, switched loop edges) from `placement`; fills
/// T_W_S, T_W_C, loop_switch, the solver figures and the report of `result`.
void relaxPlacedSessions(const std::vector<GraphSession>& sessions,
                         const std::vector<GraphLoop>& loops, const PoseGraphConfig& config,
                         const Placement& placement, PoseGraphResult& result);

}  // namespace strata::align::internal
