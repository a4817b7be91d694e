// Multi-session pose graph: input checks, placement by loop consensus, relaxation in Ceres
// (the steps in internal/pose_graph_steps.h).
#include "strata/align/pose_graph.h"

#include <Eigen/Cholesky>
#include <chrono>
#include <cmath>

#include "strata/align/internal/pose_graph_steps.h"
#include "strata/core/error.h"
#include "strata/core/validate.h"

namespace strata::align {
void PoseGraphConfig::validate() const {
  const store::Matrix6d& info = default_odometry_information;
  if (!info.allFinite() || (info - info.transpose()).norm() > 1e-9 * info.norm() ||
      info.llt().info() != Eigen::Success) {
    throw InputError(
        "PoseGraphConfig.default_odometry_information must be finite, symmetric and positive "
        "definite");
  }
  requirePositive(switch_prior_weight, "PoseGraphConfig", "switch_prior_weight");
  if (!(switch_accept >= 0.0 && switch_accept < 1.0)) {
    throw InputError("PoseGraphConfig.switch_accept must be in [0, 1), not " +
                     std::to_string(switch_accept));
  }
  requirePositive(consensus_translation_m, "PoseGraphConfig", "consensus_translation_m");
  requirePositive(consensus_rotation_rad, "PoseGraphConfig", "consensus_rotation_rad");
  if (min_consensus_loops < 1) throw InputError("PoseGraphConfig.min_consensus_loops must be >= 1");
  if (max_iterations < 1) throw InputError("PoseGraphConfig.max_iterations must be >= 1");
  if (threads < 1) throw InputError("PoseGraphConfig.threads must be >= 1");
}

PoseGraphResult optimisePoseGraph(const std::vector<GraphSession>& sessions,
                                  const std::vector<GraphLoop>& loops,
                                  const PoseGraphConfig& config) {
  config.validate();
  internal::checkPoseGraphInput(sessions, loops);
  const auto start = std::chrono::steady_clock::now();
  const internal::Placement placement = internal::placeSessions(sessions, loops, config);
  PoseGraphResult result;
  internal::relaxPlacedSessions(sessions, loops, config, placement, result);
  result.loop_accepted.assign(loops.size(), false);
  for (std::size_t l = 0; l < loops.size(); ++l) {
    result.loop_accepted[l] = placement.in_solve[l] && result.loop_switch[l] > config.switch_accept;
  }
  result.solve_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

}  // namespace strata::align
