// Input checks of optimisePoseGraph: every error names the session, keyframe or loop at fault.
#include <Eigen/Cholesky>
#include <string>

#include "strata/align/internal/pose_graph_steps.h"
#include "strata/core/error.h"

namespace strata::align::internal {
namespace {

bool isRigid(const Eigen::Isometry3d& T) {
  if (!T.matrix().allFinite()) return false;
  const Eigen::Matrix3d R = T.linear();
  // NOTE: 1e-6 admits poses parsed from text with ~9 significant digits.
  return (R.transpose() * R - Eigen::Matrix3d::Identity()).norm() < 1e-6 && R.determinant() > 0.0;
}

void checkInformation(const store::Matrix6d& information, const std::string& what) {
  if (!information.allFinite()) throw InputError(what + " is not finite");
  if ((information - information.transpose()).norm() > 1e-9 * information.norm()) {
    throw InputError(what + " is not symmetric");
  }
  if (information.llt().info() != Eigen::Success) {
    throw InputError(what + " is not positive definite");
  }
}

void checkSession(const GraphSession& session, std::size_t index) {
  const std::string name = "session " + std::to_string(index);
  if (session.T_S_C.empty()) throw InputError(name + " has no keyframes");
  for (std::size_t k = 0; k < session.T_S_C.size(); ++k) {
    if (!isRigid(session.T_S_C[k])) {
      throw InputError(name + " keyframe " + std::to_string(k) +
                       ": T_S_C is not a finite rigid transform");
    }
  }
  const std::size_t edges = session.T_S_C.size() - 1;
  if (!session.odometry_information.empty() && session.odometry_information.size() != edges) {
    throw InputError(name + ": " + std::to_string(session.odometry_information.size()) +
                     " odometry information matrices for " + std::to_string(edges) +
                     " odometry edges (give one per edge or none)");
  }
  for (std::size_t k = 0; k < session.odometry_information.size(); ++k) {
    checkInformation(session.odometry_information[k],
                     name + " odometry edge " + std::to_string(k) + " information");
  }
}

void checkLoopEnd(const std::vector<GraphSession>& sessions, std::size_t session,
                  std::size_t keyframe, const std::string& name, const char* side) {
  if (session >= sessions.size()) {
    throw InputError(name + ": session_" + side + " " + std::to_string(session) +
                     " does not exist (" + std::to_string(sessions.size()) + " sessions)");
  }
  if (keyframe >= sessions[session].T_S_C.size()) {
    throw InputError(name + ": keyframe_" + side + " " + std::to_string(keyframe) +
                     " does not exist in session " + std::to_string(session) + " (" +
                     std::to_string(sessions[session].T_S_C.size()) + " keyframes)");
  }
}

}  // namespace

void checkPoseGraphInput(const std::vector<GraphSession>& sessions,
                         const std::vector<GraphLoop>& loops) {
  if (sessions.empty()) throw InputError("pose graph: no sessions");
  for (std::size_t s = 0; s < sessions.size(); ++s) checkSession(sessions[s], s);
  for (std::size_t l = 0; l < loops.size(); ++l) {
    const GraphLoop& loop = loops[l];
    const std::string name = "loop " + std::to_string(l);
    checkLoopEnd(sessions, loop.session_a, loop.keyframe_a, name, "a");
    checkLoopEnd(sessions, loop.session_b, loop.keyframe_b, name, "b");
    if (loop.session_a == loop.session_b && loop.keyframe_a == loop.keyframe_b) {
      throw InputError(name + " joins keyframe " + std::to_string(loop.keyframe_a) +
                       " of session " + std::to_string(loop.session_a) + " to itself");
    }
    if (!isRigid(loop.T_a_b)) throw InputError(name + ": T_a_b is not a finite rigid transform");
    checkInformation(loop.information, name + " information");
  }
}

}  // namespace strata::align::internal
