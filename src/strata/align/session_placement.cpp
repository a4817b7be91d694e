// Initial placement of the sessions by loop consensus. Every loop from an unplaced session j to a
// placed one implies a pose for j's first keyframe; the largest set of loops whose implied poses
// agree (within the consensus thresholds) places j when it holds at least min_consensus_loops.
// NOTE: a vote, not a least-squares fit: a few false loops, even ones that agree among themselves,
// are out-voted by the true ones instead of being averaged into the placement, and a session that
// only false or too few loops join stays unaligned rather than being forced somewhere.
#include <Eigen/SVD>
#include <cmath>

#include "strata/align/internal/pose_graph_steps.h"

namespace strata::align::internal {
namespace {

using Eigen::Isometry3d;

struct Vote {
  std::size_t loop = 0;
  Isometry3d T_W_C0;  // the pose the loop implies for the session's first keyframe
};

/// The first keyframe pose of `loop`'s session on side b (toward_b) or side a, from the other
/// side's session placement T_W_S_from.
Isometry3d impliedFirstPose(const GraphLoop& loop, const std::vector<GraphSession>& sessions,
                            const Isometry3d& T_W_S_from, bool toward_b) {
  if (toward_b) {
    const GraphSession& a = sessions[loop.session_a];
    const GraphSession& b = sessions[loop.session_b];
    const Isometry3d T_W_Cb = T_W_S_from * a.T_S_C[loop.keyframe_a] * loop.T_a_b;
    return T_W_Cb * b.T_S_C[loop.keyframe_b].inverse() * b.T_S_C.front();
  }
  const GraphSession& a = sessions[loop.session_a];
  const GraphSession& b = sessions[loop.session_b];
  const Isometry3d T_W_Ca = T_W_S_from * b.T_S_C[loop.keyframe_b] * loop.T_a_b.inverse();
  return T_W_Ca * a.T_S_C[loop.keyframe_a].inverse() * a.T_S_C.front();
}

bool agree(const Isometry3d& x, const Isometry3d& y, const PoseGraphConfig& config) {
  if ((x.translation() - y.translation()).norm() > config.consensus_translation_m) return false;
  // trace(Rx^T Ry) = 1 + 2 cos(angle)
  const double trace = x.linear().cwiseProduct(y.linear()).sum();
  return trace >= 1.0 + 2.0 * std::cos(config.consensus_rotation_rad);
}

/// The largest set of votes agreeing with one of them (the first seed wins ties).
std::vector<std::size_t> largestAgreeingSet(const std::vector<Vote>& votes,
                                            const PoseGraphConfig& config) {
  std::vector<std::size_t> best;
  for (std::size_t seed = 0; seed < votes.size(); ++seed) {
    std::vector<std::size_t> set;
    for (std::size_t v = 0; v < votes.size(); ++v) {
      if (agree(votes[seed].T_W_C0, votes[v].T_W_C0, config)) set.push_back(v);
    }
    if (set.size() > best.size()) best = std::move(set);
  }
  return best;
}

/// Translation mean and chordal rotation mean (the rotation nearest the mean matrix).
Isometry3d meanPose(const std::vector<Vote>& votes, const std::vector<std::size_t>& set) {
  Eigen::Vector3d t = Eigen::Vector3d::Zero();
  Eigen::Matrix3d R_sum = Eigen::Matrix3d::Zero();
  for (std::size_t v : set) {
    t += votes[v].T_W_C0.translation();
    R_sum += votes[v].T_W_C0.linear();
  }
  const Eigen::JacobiSVD<Eigen::Matrix3d> svd(R_sum, Eigen::ComputeFullU | Eigen::ComputeFullV);
  Eigen::Matrix3d D = Eigen::Matrix3d::Identity();
  D(2, 2) = (svd.matrixU() * svd.matrixV().transpose()).determinant() < 0.0 ? -1.0 : 1.0;
  Isometry3d mean = Isometry3d::Identity();
  mean.linear() = svd.matrixU() * D * svd.matrixV().transpose();
  mean.translation() = t / static_cast<double>(set.size());
  return mean;
}

/// The votes of every loop joining unplaced session j to a placed session.
std::vector<Vote> votesFor(std::size_t j, const std::vector<GraphSession>& sessions,
                           const std::vector<GraphLoop>& loops,
                           const std::vector<std::optional<Isometry3d>>& T_W_S) {
  std::vector<Vote> votes;
  for (std::size_t l = 0; l < loops.size(); ++l) {
    const GraphLoop& loop = loops[l];
    if (loop.session_b == j && loop.session_a != j && T_W_S[loop.session_a]) {
      votes.push_back({l, impliedFirstPose(loop, sessions, *T_W_S[loop.session_a], true)});
    } else if (loop.session_a == j && loop.session_b != j && T_W_S[loop.session_b]) {
      votes.push_back({l, impliedFirstPose(loop, sessions, *T_W_S[loop.session_b], false)});
    }
  }
  return votes;
}

struct Candidate {
  std::size_t session = 0;
  std::size_t support = 0;
  Isometry3d T_W_S = Isometry3d::Identity();
};

/// The unplaced session with the most agreeing loops, if any reaches min_consensus_loops.
std::optional<Candidate> bestCandidate(const std::vector<GraphSession>& sessions,
                                       const std::vector<GraphLoop>& loops,
                                       const std::vector<std::optional<Isometry3d>>& T_W_S,
                                       const PoseGraphConfig& config) {
  std::optional<Candidate> best;
  for (std::size_t j = 0; j < sessions.size(); ++j) {
    if (T_W_S[j]) continue;
    const std::vector<Vote> votes = votesFor(j, sessions, loops, T_W_S);
    const std::vector<std::size_t> set = largestAgreeingSet(votes, config);
    if (set.size() < static_cast<std::size_t>(config.min_consensus_loops)) continue;
    if (best && set.size() <= best->support) continue;
    const Isometry3d T_W_C0 = meanPose(votes, set);
    best = Candidate{j, set.size(), T_W_C0 * sessions[j].T_S_C.front().inverse()};
  }
  return best;
}

}  // namespace

Placement placeSessions(const std::vector<GraphSession>& sessions,
                        const std::vector<GraphLoop>& loops, const PoseGraphConfig& config) {
  Placement placement;
  placement.T_W_S.assign(sessions.size(), std::nullopt);
  placement.T_W_S[0] = Isometry3d::Identity();
  // Most supported session first: its placement then lends more votes to the rest.
  while (const auto candidate = bestCandidate(sessions, loops, placement.T_W_S, config)) {
    placement.T_W_S[candidate->session] = candidate->T_W_S;
  }
  placement.initial_switch.assign(loops.size(), 0.0);
  placement.in_solve.assign(loops.size(), false);
  for (std::size_t l = 0; l < loops.size(); ++l) {
    const GraphLoop& loop = loops[l];
    const auto& T_W_Sa = placement.T_W_S[loop.session_a];
    const auto& T_W_Sb = placement.T_W_S[loop.session_b];
    if (!T_W_Sa || !T_W_Sb) continue;
    placement.in_solve[l] = true;
    const Isometry3d placed_T_W_Cb0 = *T_W_Sb * sessions[loop.session_b].T_S_C.front();
    const bool on = agree(impliedFirstPose(loop, sessions, *T_W_Sa, true), placed_T_W_Cb0, config);
    placement.initial_switch[l] = on ? 1.0 : 0.0;
  }
  return placement;
}

}  // namespace strata::align::internal
