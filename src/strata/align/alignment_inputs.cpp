// Input checks and keyframe loading of the session alignment.
#include <algorithm>
#include <atomic>
#include <cmath>
#include <exception>
#include <mutex>

#include "strata/align/internal/alignment_steps.h"
#include "strata/core/error.h"
#include "strata/core/parallel_for.h"

namespace strata::align::detail {
namespace {

bool finitePose(const Eigen::Isometry3d& T) { return T.matrix().allFinite(); }

void validateSession(const AlignSession& s, std::size_t index) {
  const std::string what = "session " + std::to_string(index) + " '" + s.name + "'";
  if (s.frames == nullptr || s.frames->size() == 0) throw InputError(what + ": no frames");
  const std::size_t n = s.frames->size();
  if (s.frame_T_S_C.size() != n || s.frame_timestamps_s.size() != n) {
    throw InputError(what + ": " + std::to_string(n) + " frames but " +
                     std::to_string(s.frame_T_S_C.size()) + " odometry poses and " +
                     std::to_string(s.frame_timestamps_s.size()) + " timestamps");
  }
  for (std::size_t i = 0; i < n; ++i) {
    if (!finitePose(s.frame_T_S_C[i]) || !std::isfinite(s.frame_timestamps_s[i])) {
      throw InputError(what + ": frame " + std::to_string(i) + " has a non-finite pose or time");
    }
    if (i > 0 && s.frame_timestamps_s[i] < s.frame_timestamps_s[i - 1]) {
      throw InputError(what + ": frame timestamps decrease at frame " + std::to_string(i));
    }
  }
  if (s.keyframes.empty()) throw InputError(what + ": no keyframes");
  for (std::size_t k = 0; k < s.keyframes.size(); ++k) {
    if (s.keyframes[k] >= n || (k > 0 && s.keyframes[k] <= s.keyframes[k - 1])) {
      throw InputError(what + ": keyframe " + std::to_string(k) + " (frame " +
                       std::to_string(s.keyframes[k]) + ") is out of range or out of order");
    }
  }
  if (!s.odometry_information.empty() && s.odometry_information.size() + 1 != s.keyframes.size()) {
    throw InputError(what + ": " + std::to_string(s.odometry_information.size()) +
                     " odometry informations for " + std::to_string(s.keyframes.size()) +
                     " keyframes (needs one per consecutive pair)");
  }
  if (!s.stored_features.empty() && s.stored_features.size() != s.keyframes.size()) {
    throw InputError(what + ": stored features for " + std::to_string(s.stored_features.size()) +
                     " of " + std::to_string(s.keyframes.size()) + " keyframes");
  }
}

LoadedKeyframe loadOne(const AlignSession& s, std::size_t session, std::size_t k,
                       const AlignConfig& align_config) {
  const FeatureConfig& config = align_config.features;
  LoadedKeyframe out;
  out.session = session;
  out.keyframe = k;
  out.timestamp_s = s.frame_timestamps_s[s.keyframes[k]];
  out.intrinsics = s.frames->intrinsics();
  RgbdFrame frame = s.frames->load(s.keyframes[k]);
  out.depth = std::move(frame.depth);
  if (!s.stored_features.empty() && s.stored_features[k]) {
    out.features = liftFeatures(*s.stored_features[k], out.depth, out.intrinsics, config);
  } else {
    if (frame.color.empty()) {
      throw InputError("session '" + s.name + "' frame " + std::to_string(s.keyframes[k]) +
                       " (" + frame.name + ") has no colour image: features need one");
    }
    out.features = extractFeatures(frame.color, out.depth, out.intrinsics, config);
  }
  if (align_config.surface_candidates_per_keyframe > 0)
    out.surface = describeSurface(out.depth, out.intrinsics, align_config.surface);
  return out;
}

}  // namespace

void validateSessions(const std::vector<AlignSession>& sessions) {
  if (sessions.empty()) throw InputError("alignment needs at least one session");
  for (std::size_t i = 0; i < sessions.size(); ++i) validateSession(sessions[i], i);
}

std::vector<LoadedKeyframe> loadKeyframes(const std::vector<AlignSession>& sessions,
                                          const AlignConfig& config,
                                          const AlignProgress& progress) {
  std::vector<std::pair<std::size_t, std::size_t>> jobs;  // (session, keyframe)
  for (std::size_t s = 0; s < sessions.size(); ++s)
    for (std::size_t k = 0; k < sessions[s].keyframes.size(); ++k) jobs.emplace_back(s, k);
  std::vector<LoadedKeyframe> loaded(jobs.size());
  std::atomic<std::size_t> done{0};
  std::mutex report_mutex;
  parallelForEach(jobs.size(), std::max(1, config.threads), [&](std::size_t j) {
    loaded[j] = loadOne(sessions[jobs[j].first], jobs[j].first, jobs[j].second, config);
    const std::size_t finished = ++done;
    if (progress) {
      std::lock_guard<std::mutex> lock(report_mutex);
      progress("features", finished, jobs.size());
    }
  });
  return loaded;
}

}  // namespace strata::align::detail
