// Scoring an alignment against the truth.
#include "strata/align/alignment_eval.h"

#include <cmath>
#include <nlohmann/json.hpp>

#include "strata/core/error.h"
#include "strata/trajectory/trajectory_alignment.h"

namespace strata::align {
namespace {

constexpr double kRadToDeg = 180.0 / M_PI;

double angleDeg(const Eigen::Matrix3d& R) { return Eigen::AngleAxisd(R).angle() * kRadToDeg; }

struct Pairs {
  std::vector<Eigen::Isometry3d> estimate, truth;
  std::vector<std::size_t> session;
};

/// RMSE (and max) of the positions after one SE(3) fit over all pairs; per-session RMSE too.
double fitRmse(const Pairs& pairs, std::size_t sessions, double* max_m,
               std::vector<double>* per_session) {
  if (pairs.estimate.empty()) return NAN;
  const trajectory::SimilarityTransform fit =
      trajectory::alignTrajectory(pairs.estimate, pairs.truth, trajectory::Alignment::kSE3);
  double sum = 0.0, worst = 0.0;
  std::vector<double> sums(sessions, 0.0);
  std::vector<std::size_t> counts(sessions, 0);
  for (std::size_t i = 0; i < pairs.estimate.size(); ++i) {
    const double e2 =
        (fit.apply(pairs.estimate[i].translation()) - pairs.truth[i].translation()).squaredNorm();
    sum += e2;
    worst = std::max(worst, std::sqrt(e2));
    sums[pairs.session[i]] += e2;
    ++counts[pairs.session[i]];
  }
  if (max_m) *max_m = worst;
  if (per_session) {
    per_session->assign(sessions, NAN);
    for (std::size_t s = 0; s < sessions; ++s)
      if (counts[s] > 0) (*per_session)[s] = std::sqrt(sums[s] / counts[s]);
  }
  return std::sqrt(sum / pairs.estimate.size());
}

Eigen::Isometry3d trueKeyframe(const SessionTruth& truth, const AlignedSession& s, std::size_t k,
                               bool* found) {
  const auto& pose = truth[s.keyframes[k]];
  *found = pose.has_value();
  return pose.value_or(Eigen::Isometry3d::Identity());
}

void scoreLoops(const AlignResult& result, const std::vector<SessionTruth>& truth,
                const LoopTruthConfig& c, AlignmentScore& score) {
  for (const AlignLoop& loop : result.loops) {
    bool found_a = false, found_b = false;
    const Eigen::Isometry3d T_W_a =
        trueKeyframe(truth[loop.session_a], result.sessions[loop.session_a], loop.keyframe_a, &found_a);
    const Eigen::Isometry3d T_W_b =
        trueKeyframe(truth[loop.session_b], result.sessions[loop.session_b], loop.keyframe_b, &found_b);
    LoopScore ls;
    if (found_a && found_b) {
      const Eigen::Isometry3d error = (T_W_a.inverse() * T_W_b).inverse() * loop.measurement.T_a_b;
      ls.translation_error_m = error.translation().norm();
      ls.rotation_error_deg = angleDeg(error.linear());
      ls.is_true = ls.translation_error_m <= c.max_translation_error_m &&
                   ls.rotation_error_deg <= c.max_rotation_error_deg;
    }
    score.loops.push_back(ls);
    if (loop.accepted) ++(ls.is_true ? score.accepted_true : score.accepted_false);
    else ++(ls.is_true ? score.switched_off_true : score.switched_off_false);
  }
  const std::size_t accepted = score.accepted_true + score.accepted_false;
  if (accepted > 0) score.loop_precision = double(score.accepted_true) / double(accepted);
}

/// Keyframe-level recall: does a keyframe that could close a loop (by the truth) close one?
void scoreRecall(const AlignResult& result, const std::vector<SessionTruth>& truth,
                 const AlignConfig& config, const LoopTruthConfig& c, AlignmentScore& score) {
  struct Key { std::size_t s, k; double t; Eigen::Isometry3d T_W_C; };
  std::vector<Key> keys;
  for (std::size_t s = 0; s < result.sessions.size(); ++s) {
    const AlignedSession& session = result.sessions[s];
    for (std::size_t k = 0; k < session.keyframes.size(); ++k) {
      bool found = false;
      const Eigen::Isometry3d T = trueKeyframe(truth[s], session, k, &found);
      if (found) keys.push_back({s, k, session.keyframe_timestamps_s[k], T});
    }
  }
  std::vector<std::vector<bool>> closed(result.sessions.size());
  for (std::size_t s = 0; s < result.sessions.size(); ++s)
    closed[s].assign(result.sessions[s].keyframes.size(), false);
  for (std::size_t l = 0; l < result.loops.size(); ++l) {
    if (!result.loops[l].accepted || !score.loops[l].is_true) continue;
    closed[result.loops[l].session_a][result.loops[l].keyframe_a] = true;
    closed[result.loops[l].session_b][result.loops[l].keyframe_b] = true;
  }
  const double cos_max = std::cos(c.overlap_angle_deg / kRadToDeg);
  for (const Key& a : keys) {
    bool opportunity = false;
    for (const Key& b : keys) {
      if (&a == &b) continue;
      if (a.s == b.s && (!config.intra_session_loops ||
                         std::abs(a.t - b.t) < config.min_intra_session_gap_s)) continue;
      if ((a.T_W_C.translation() - b.T_W_C.translation()).norm() > c.overlap_distance_m) continue;
      if (a.T_W_C.linear().col(2).dot(b.T_W_C.linear().col(2)) < cos_max) continue;
      opportunity = true;
      break;
    }
    if (!opportunity) continue;
    ++score.keyframes_with_opportunity;
    if (closed[a.s][a.k]) ++score.keyframes_closed;
  }
  if (score.keyframes_with_opportunity > 0)
    score.loop_recall = double(score.keyframes_closed) / double(score.keyframes_with_opportunity);
}

}  // namespace

AlignmentScore scoreAlignment(const AlignResult& result, const std::vector<SessionTruth>& truth,
                              const AlignConfig& config, const LoopTruthConfig& loop_truth) {
  if (truth.size() != result.sessions.size()) {
    throw InputError("alignment score: truth for " + std::to_string(truth.size()) + " of " +
                     std::to_string(result.sessions.size()) + " sessions");
  }
  AlignmentScore score;
  const std::size_t n = result.sessions.size();
  Pairs before, after;
  std::vector<Pairs> own(n);
  for (std::size_t s = 0; s < n; ++s) {
    const AlignedSession& session = result.sessions[s];
    if (truth[s].size() != session.frame_T_S_C.size()) {
      throw InputError("alignment score: session " + std::to_string(s) + " has " +
                       std::to_string(session.frame_T_S_C.size()) + " frames but " +
                       std::to_string(truth[s].size()) + " true poses");
    }
    SessionScore ss;
    ss.aligned = session.aligned;
    ss.frames = session.frame_T_S_C.size();
    for (std::size_t i = 0; i < truth[s].size(); ++i) {
      if (!truth[s][i]) continue;
      before.estimate.push_back(session.frame_T_S_C[i]), before.truth.push_back(*truth[s][i]);
      before.session.push_back(s);
      own[s].estimate.push_back(session.frame_T_S_C[i]), own[s].truth.push_back(*truth[s][i]);
      own[s].session.push_back(0);
      if (session.aligned) {
        after.estimate.push_back(session.frame_T_W_C[i]), after.truth.push_back(*truth[s][i]);
        after.session.push_back(s);
      }
    }
    ss.ate_drift_rmse_m = fitRmse(own[s], 1, nullptr, nullptr);
    score.sessions.push_back(ss);
    if (session.aligned) ++score.aligned_sessions;
  }
  score.ate_before_rmse_m = fitRmse(before, n, nullptr, nullptr);
  std::vector<double> per_session;
  score.ate_after_rmse_m = fitRmse(after, n, &score.ate_after_max_m, &per_session);
  for (std::size_t s = 0; s < n && !per_session.empty(); ++s)
    score.sessions[s].ate_after_rmse_m = per_session[s];
  // T_W_S against the truth's, relative to the anchor: the true session-to-world transform is
  // the true first pose times the inverse odometry first pose (odometry starts exact).
  auto trueT_W_S = [&](std::size_t s) -> std::optional<Eigen::Isometry3d> {
    if (truth[s].empty() || !truth[s].front()) return std::nullopt;
    return *truth[s].front() * result.sessions[s].frame_T_S_C.front().inverse();
  };
  const auto anchor = trueT_W_S(0);
  for (std::size_t s = 0; s < n && anchor; ++s) {
    const auto T_true = trueT_W_S(s);
    if (!T_true || !result.sessions[s].T_W_S) continue;
    // Measured at the session's first camera: an offset's translation error depends on where it
    // is measured, and the odometry origin may lie metres from the data.
    const Eigen::Isometry3d& T_S_C0 = result.sessions[s].frame_T_S_C.front();
    const Eigen::Isometry3d error =
        (anchor->inverse() * *T_true * T_S_C0).inverse() * *result.sessions[s].T_W_S * T_S_C0;
    score.sessions[s].T_W_S_error_m = error.translation().norm();
    score.sessions[s].T_W_S_error_deg = angleDeg(error.linear());
  }
  scoreLoops(result, truth, loop_truth, score);
  scoreRecall(result, truth, config, loop_truth, score);
  return score;
}

std::string alignmentScoreJson(const AlignmentScore& s) {
  using Json = nlohmann::ordered_json;
  Json sessions = Json::array();
  for (const SessionScore& ss : s.sessions) {
    Json session;
    session["aligned"] = ss.aligned;
    session["frames"] = ss.frames;
    session["ate_after_rmse_m"] = ss.ate_after_rmse_m;
    session["ate_drift_only_rmse_m"] = ss.ate_drift_rmse_m;
    session["T_W_S_error_m"] = ss.T_W_S_error_m;
    session["T_W_S_error_deg"] = ss.T_W_S_error_deg;
    sessions.push_back(std::move(session));
  }
  Json j;
  j["aligned_sessions"] = s.aligned_sessions;
  j["ate_before_rmse_m"] = s.ate_before_rmse_m;
  j["ate_after_rmse_m"] = s.ate_after_rmse_m;
  j["ate_after_max_m"] = s.ate_after_max_m;
  j["loops_accepted_true"] = s.accepted_true;
  j["loops_accepted_false"] = s.accepted_false;
  j["loops_switched_off_true"] = s.switched_off_true;
  j["loops_switched_off_false"] = s.switched_off_false;
  j["loop_precision"] = s.loop_precision;
  j["keyframes_with_loop_opportunity"] = s.keyframes_with_opportunity;
  j["keyframes_closed"] = s.keyframes_closed;
  j["loop_recall"] = s.loop_recall;
  j["sessions"] = std::move(sessions);
  // NaN (no pairs to fit, no accepted loop) comes out as null.
  return j.dump(2, ' ', false, Json::error_handler_t::replace);
}

}  // namespace strata::align
