// Relaxation of the placed sessions: one Ceres problem over every placed keyframe pose, odometry
// edges between consecutive keyframes, switched loop edges with their switch priors. The first
// keyframe of session 0 is held constant (the gauge: T_W_S0 = identity).
#include <ceres/ceres.h>

#include <Eigen/Cholesky>

#include "strata/align/internal/pose_graph_costs.h"
#include "strata/align/internal/pose_graph_steps.h"

namespace strata::align::internal {
namespace {

using Eigen::Isometry3d;

struct PoseBlock {
  Eigen::Vector3d p_W_C;
  Eigen::Quaterniond q_W_C;  // coeffs() in x y z w order, as EigenQuaternionManifold expects
};

store::Matrix6d sqrtInformation(const store::Matrix6d& information) {
  return information.llt().matrixU();  // information = U^T U, so |U e|^2 = e^T information e
}

/// The poses the placement gives every keyframe of the placed sessions (empty when unplaced).
std::vector<std::vector<PoseBlock>> initialPoses(const std::vector<GraphSession>& sessions,
                                                 const Placement& placement) {
  std::vector<std::vector<PoseBlock>> poses(sessions.size());
  for (std::size_t s = 0; s < sessions.size(); ++s) {
    if (!placement.T_W_S[s]) continue;
    for (const Isometry3d& T_S_C : sessions[s].T_S_C) {
      const Isometry3d T_W_C = *placement.T_W_S[s] * T_S_C;
      poses[s].push_back({T_W_C.translation(), Eigen::Quaterniond(T_W_C.linear()).normalized()});
    }
  }
  return poses;
}

void addOdometryEdges(const std::vector<GraphSession>& sessions, const PoseGraphConfig& config,
                      std::vector<std::vector<PoseBlock>>& poses, ceres::Problem& problem,
                      ceres::Manifold* quaternion_manifold) {
  const store::Matrix6d default_sqrt = sqrtInformation(config.default_odometry_information);
  for (std::size_t s = 0; s < sessions.size(); ++s) {
    std::vector<PoseBlock>& pose = poses[s];
    for (PoseBlock& block : pose) {
      problem.AddParameterBlock(block.p_W_C.data(), 3);
      problem.AddParameterBlock(block.q_W_C.coeffs().data(), 4, quaternion_manifold);
    }
    for (std::size_t k = 0; k + 1 < pose.size(); ++k) {
      const GraphSession& session = sessions[s];
      const Isometry3d T_k_k1 = session.T_S_C[k].inverse() * session.T_S_C[k + 1];
      const store::Matrix6d sqrt_info = session.odometry_information.empty()
                                            ? default_sqrt
                                            : sqrtInformation(session.odometry_information[k]);
      problem.AddResidualBlock(EdgeCost::create(T_k_k1, sqrt_info), nullptr, pose[k].p_W_C.data(),
                               pose[k].q_W_C.coeffs().data(), pose[k + 1].p_W_C.data(),
                               pose[k + 1].q_W_C.coeffs().data());
    }
  }
}

void addLoopEdges(const std::vector<GraphLoop>& loops, const PoseGraphConfig& config,
                  const Placement& placement, std::vector<std::vector<PoseBlock>>& poses,
                  std::vector<double>& switches, ceres::Problem& problem) {
  for (std::size_t l = 0; l < loops.size(); ++l) {
    if (!placement.in_solve[l]) continue;
    const GraphLoop& loop = loops[l];
    PoseBlock& a = poses[loop.session_a][loop.keyframe_a];
    PoseBlock& b = poses[loop.session_b][loop.keyframe_b];
    double* s = &switches[l];
    problem.AddResidualBlock(
        SwitchedEdgeCost::create(loop.T_a_b, sqrtInformation(loop.information)), nullptr,
        a.p_W_C.data(), a.q_W_C.coeffs().data(), b.p_W_C.data(), b.q_W_C.coeffs().data(), s);
    problem.AddResidualBlock(SwitchPriorCost::create(config.switch_prior_weight), nullptr, s);
    problem.SetParameterLowerBound(s, 0, 0.0);
    problem.SetParameterUpperBound(s, 0, 1.0);
  }
}

ceres::Solver::Options solverOptions(const PoseGraphConfig& config) {
  ceres::Solver::Options options;
  // Debian's Ceres is built with SuiteSparse: sparse Cholesky of the normal equations suits a
  // pose graph (a banded chain per session plus the loops' off-diagonal blocks).
  options.linear_solver_type = ceres::SPARSE_NORMAL_CHOLESKY;
  options.max_num_iterations = config.max_iterations;
  options.num_threads = config.threads;
  options.logging_type = ceres::SILENT;
  options.minimizer_progress_to_stdout = false;
  return options;
}

}  // namespace

void relaxPlacedSessions(const std::vector<GraphSession>& sessions,
                         const std::vector<GraphLoop>& loops, const PoseGraphConfig& config,
                         const Placement& placement, PoseGraphResult& result) {
  std::vector<std::vector<PoseBlock>> poses = initialPoses(sessions, placement);
  std::vector<double> switches = placement.initial_switch;
  ceres::EigenQuaternionManifold quaternion_manifold;
  ceres::Problem::Options problem_options;
  problem_options.manifold_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
  ceres::Problem problem(problem_options);
  addOdometryEdges(sessions, config, poses, problem, &quaternion_manifold);
  addLoopEdges(loops, config, placement, poses, switches, problem);
  problem.SetParameterBlockConstant(poses[0][0].p_W_C.data());
  problem.SetParameterBlockConstant(poses[0][0].q_W_C.coeffs().data());

  ceres::Solver::Summary summary;
  ceres::Solve(solverOptions(config), &problem, &summary);

  result.T_W_S.assign(sessions.size(), std::nullopt);
  result.T_W_C.assign(sessions.size(), {});
  for (std::size_t s = 0; s < sessions.size(); ++s) {
    for (const PoseBlock& block : poses[s]) {
      Isometry3d T_W_C = Isometry3d::Identity();
      T_W_C.linear() = block.q_W_C.normalized().toRotationMatrix();
      T_W_C.translation() = block.p_W_C;
      result.T_W_C[s].push_back(T_W_C);
    }
    if (!poses[s].empty()) {
      result.T_W_S[s] = result.T_W_C[s].front() * sessions[s].T_S_C.front().inverse();
    }
  }
  result.loop_switch.assign(loops.size(), 0.0);
  for (std::size_t l = 0; l < loops.size(); ++l) {
    if (placement.in_solve[l]) result.loop_switch[l] = switches[l];
  }
  result.iterations = summary.num_successful_steps + summary.num_unsuccessful_steps;
  result.initial_cost = summary.initial_cost;
  result.final_cost = summary.final_cost;
  result.report = summary.BriefReport();
}

}  // namespace strata::align::internal
