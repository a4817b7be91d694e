#pragma once
// Scoring an alignment against the truth (simulated sessions, or real ones with a reference
// trajectory): absolute trajectory error in the common frame before and after, and every loop
// checked against the true relative pose. Frames: the estimate's world is the anchor session's
// odometry frame; one rigid transform (fitted over every aligned session's frames at once) takes
// it to the truth's world, so a session misplaced relative to the others shows as error, not as a
// transform of its own. Thread safety: free functions.
#include <Eigen/Geometry>
#include <optional>
#include <string>
#include <vector>

#include "strata/align/session_alignment.h"

namespace strata::align {

/// The true camera-to-world pose of each frame of one session (index-aligned with the session's
/// frames; nullopt where the truth has none).
using SessionTruth = std::vector<std::optional<Eigen::Isometry3d>>;

struct LoopTruthConfig {
  double max_translation_error_m = 0.10;  // a loop within these of the true T_a_b is true
  double max_rotation_error_deg = 5.0;
  /// Keyframes overlap (a loop opportunity, for recall) when their camera centres are within
  /// this distance and their optical axes within this angle, by the truth.
  double overlap_distance_m = 1.0;
  double overlap_angle_deg = 30.0;
};

struct SessionScore {
  bool aligned = false;
  std::size_t frames = 0;
  double ate_after_rmse_m = NAN;   // this session's frames in the common-frame fit
  double ate_drift_rmse_m = NAN;   // the odometry aligned to the truth on its own (drift only)
  /// T_W_S against the truth's (relative to the anchor), at the session's first camera: the
  /// position and orientation error of that camera placed by T_W_S.
  double T_W_S_error_m = NAN, T_W_S_error_deg = NAN;
};

struct LoopScore {
  bool is_true = false;
  double translation_error_m = 0.0, rotation_error_deg = 0.0;
};

struct AlignmentScore {
  std::vector<SessionScore> sessions;
  std::size_t aligned_sessions = 0;
  double ate_before_rmse_m = NAN;  // odometry as given (own frames), one fit for all sessions
  double ate_after_rmse_m = NAN, ate_after_max_m = NAN;  // aligned frames, one fit
  std::vector<LoopScore> loops;    // per AlignResult::loops
  std::size_t accepted_true = 0, accepted_false = 0;  // kept by the graph
  std::size_t switched_off_true = 0, switched_off_false = 0;
  double loop_precision = NAN;     // accepted_true / accepted
  /// Keyframes with a loop opportunity (by the truth, to any admissible keyframe), and of them
  /// those with an accepted true loop.
  std::size_t keyframes_with_opportunity = 0, keyframes_closed = 0;
  double loop_recall = NAN;
};

/// Scores `result` against `truth` (one per session). `config` supplies the intra-session gap
/// that made a pair admissible. InputError when a truth's size differs from its session's frames.
AlignmentScore scoreAlignment(const AlignResult& result, const std::vector<SessionTruth>& truth,
                              const AlignConfig& config, const LoopTruthConfig& loop_truth = {});

/// The score as a JSON object, indented by two spaces (no trailing newline); NaN as null.
std::string alignmentScoreJson(const AlignmentScore& score);

}  // namespace strata::align
