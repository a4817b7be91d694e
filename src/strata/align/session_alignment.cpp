// Multi-session alignment: keyframes -> features -> place candidates -> verified loops -> pose
// graph -> corrected frames.
#include "strata/align/session_alignment.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <functional>
#include <mutex>
#include <utility>

#include "strata/align/internal/alignment_steps.h"
#include "strata/core/clock.h"
#include "strata/core/error.h"
#include "strata/core/parallel_for.h"

namespace strata::align {
namespace {

using Clock = std::chrono::steady_clock;
// Loop information is capped at sigma = 5 mm / 5 mrad (see clampInformation).
constexpr double kMaxLoopInformation = 1.0 / (0.005 * 0.005);

struct Candidate {
  std::size_t a = 0, b = 0;  // indices into the loaded keyframes; a was indexed before b
  double score = 0.0;        // appearance: the place index's; surface: minus the distance
};

// The `count` admissible keyframes before q nearest by surface descriptor that are not already
// candidates of q (candidates[taken_from...]).
void addSurfaceCandidates(const std::vector<detail::LoadedKeyframe>& keyframes, std::size_t q,
                          std::size_t count, const std::function<bool(std::size_t)>& admissible,
                          std::vector<Candidate>& candidates, std::size_t taken_from) {
  std::vector<std::pair<double, std::size_t>> nearest;
  for (std::size_t k = 0; k < q; ++k) {
    if (!admissible(k)) continue;
    bool taken = false;
    for (std::size_t c = taken_from; c < candidates.size(); ++c) taken |= candidates[c].a == k;
    if (taken) continue;
    const double d = surfaceDistance(keyframes[q].surface, keyframes[k].surface);
    if (std::isfinite(d)) nearest.emplace_back(d, k);
  }
  const std::size_t n = std::min(count, nearest.size());
  std::partial_sort(nearest.begin(), nearest.begin() + static_cast<std::ptrdiff_t>(n),
                    nearest.end());
  for (std::size_t i = 0; i < n; ++i)
    candidates.push_back({nearest[i].second, q, -nearest[i].first});
}

/// Queries each keyframe against those indexed before it (so every pair is considered once),
/// then indexes it.
std::vector<Candidate> findCandidates(const std::vector<detail::LoadedKeyframe>& keyframes,
                                      const AlignConfig& config, const AlignProgress& progress) {
  PlaceIndex index(config.index);
  std::vector<Candidate> candidates;
  for (std::size_t q = 0; q < keyframes.size(); ++q) {
    const detail::LoadedKeyframe& query = keyframes[q];
    auto admissible = [&](std::size_t k) {
      const detail::LoadedKeyframe& other = keyframes[k];
      if (other.session != query.session) return true;
      return config.intra_session_loops &&
             std::abs(query.timestamp_s - other.timestamp_s) >= config.min_intra_session_gap_s;
    };
    const std::size_t first = candidates.size();
    if (index.keyframes() > 0 && query.features.size() > 0) {
      for (const PlaceCandidate& c : index.query(query.features, config.candidates_per_keyframe,
                                                 config.min_votes, admissible)) {
        candidates.push_back({c.keyframe, q, c.score});
      }
    }
    if (config.surface_candidates_per_keyframe > 0) {
      addSurfaceCandidates(keyframes, q, config.surface_candidates_per_keyframe, admissible,
                           candidates, first);
    }
    if (query.features.size() > 0) index.add(q, query.features);
    if (progress) progress("place recognition", q + 1, keyframes.size());
  }
  return candidates;
}

std::vector<LoopMeasurement> verifyAll(const std::vector<detail::LoadedKeyframe>& keyframes,
                                       const std::vector<Candidate>& candidates,
                                       const AlignConfig& config, const AlignProgress& progress) {
  std::vector<LoopMeasurement> out(candidates.size());
  std::atomic<std::size_t> done{0};
  std::mutex progress_mutex;
  parallelForEach(candidates.size(), std::max(1, config.threads), [&](std::size_t j) {
    const detail::LoadedKeyframe& a = keyframes[candidates[j].a];
    const detail::LoadedKeyframe& b = keyframes[candidates[j].b];
    const bool surfaces = config.surface_candidates_per_keyframe > 0;
    out[j] = verifyLoop({&a.features, &a.depth, a.intrinsics, surfaces ? &a.surface : nullptr},
                        {&b.features, &b.depth, b.intrinsics, surfaces ? &b.surface : nullptr},
                        config.verify);
    const std::size_t finished = ++done;
    if (progress) {
      std::lock_guard<std::mutex> lock(progress_mutex);
      progress("verification", finished, candidates.size());
    }
  });
  return out;
}

std::vector<GraphSession> graphSessions(const std::vector<AlignSession>& sessions) {
  std::vector<GraphSession> out(sessions.size());
  for (std::size_t s = 0; s < sessions.size(); ++s) {
    for (std::size_t frame : sessions[s].keyframes)
      out[s].T_S_C.push_back(sessions[s].frame_T_S_C[frame]);
    out[s].odometry_information = sessions[s].odometry_information;
  }
  return out;
}

void fillSessions(const std::vector<AlignSession>& sessions,
                  std::vector<detail::LoadedKeyframe>& keyframes, AlignResult& result) {
  result.sessions.resize(sessions.size());
  for (std::size_t s = 0; s < sessions.size(); ++s) {
    AlignedSession& out = result.sessions[s];
    const AlignSession& in = sessions[s];
    out.frame_T_S_C = in.frame_T_S_C;
    out.frame_timestamps_s = in.frame_timestamps_s;
    out.keyframes = in.keyframes;
    for (std::size_t frame : in.keyframes)
      out.keyframe_timestamps_s.push_back(in.frame_timestamps_s[frame]);
    out.T_W_S = result.graph.T_W_S[s];
    out.aligned = out.T_W_S.has_value();
    if (out.aligned) {
      out.keyframe_T_W_C = result.graph.T_W_C[s];
      out.frame_T_W_C = detail::correctFrames(in.frame_timestamps_s, in.frame_T_S_C, in.keyframes,
                                              out.keyframe_T_W_C);
    }
  }
  for (detail::LoadedKeyframe& k : keyframes)
    result.sessions[k.session].features.push_back(std::move(k.features));
}

}  // namespace

void AlignConfig::validate() const {
  features.validate();
  surface.validate();
  index.validate();
  verify.validate();
  graph.validate();
  if (candidates_per_keyframe == 0) throw InputError("align: candidates_per_keyframe must be >= 1");
  if (min_votes < 1) throw InputError("align: min_votes must be >= 1");
  if (!(min_intra_session_gap_s >= 0.0))
    throw InputError("align: min_intra_session_gap_s must be >= 0");
  if (threads < 1) throw InputError("align: threads must be >= 1");
}

AlignResult alignSessions(const std::vector<AlignSession>& sessions, const AlignConfig& config,
                          const AlignProgress& progress) {
  config.validate();
  detail::validateSessions(sessions);
  AlignResult result;
  auto start = Clock::now();
  std::vector<detail::LoadedKeyframe> keyframes = detail::loadKeyframes(sessions, config, progress);
  result.times.features_s = secondsSince(start);
  result.times.keyframes = keyframes.size();

  start = Clock::now();
  const std::vector<Candidate> candidates = findCandidates(keyframes, config, progress);
  result.times.retrieval_s = secondsSince(start);

  start = Clock::now();
  const std::vector<LoopMeasurement> measured = verifyAll(keyframes, candidates, config, progress);
  result.times.verification_s = secondsSince(start);
  result.times.verifications = result.candidates = candidates.size();

  std::vector<GraphLoop> graph_loops;
  for (std::size_t j = 0; j < candidates.size(); ++j) {
    if (!measured[j].accepted) {
      result.rejection_reasons.push_back(measured[j].reason);
      continue;
    }
    if (!measured[j].T_a_b.matrix().allFinite() || !measured[j].information.allFinite()) {
      // Never expected of the verifier; a loop the graph would refuse must not end the run.
      result.rejection_reasons.push_back("non-finite measurement");
      continue;
    }
    const detail::LoadedKeyframe& a = keyframes[candidates[j].a];
    const detail::LoadedKeyframe& b = keyframes[candidates[j].b];
    AlignLoop loop{a.session, a.keyframe, b.session, b.keyframe, measured[j], candidates[j].score};
    loop.measurement.information =
        detail::clampInformation(measured[j].information, kMaxLoopInformation);
    graph_loops.push_back({a.session, a.keyframe, b.session, b.keyframe, measured[j].T_a_b,
                           loop.measurement.information});
    result.loops.push_back(std::move(loop));
  }

  if (progress) progress("pose graph", 0, 1);
  start = Clock::now();
  result.graph = optimisePoseGraph(graphSessions(sessions), graph_loops, config.graph);
  result.times.graph_s = secondsSince(start);
  if (progress) progress("pose graph", 1, 1);
  for (std::size_t l = 0; l < result.loops.size(); ++l) {
    result.loops[l].switch_value = result.graph.loop_switch[l];
    result.loops[l].accepted = result.graph.loop_accepted[l];
  }
  fillSessions(sessions, keyframes, result);
  return result;
}

AlignSession sessionFromDataset(const Dataset& dataset, const Dataset* frames) {
  AlignSession s;
  s.name = dataset.name();
  s.frames = frames != nullptr ? frames : &dataset;
  if (s.frames->size() != dataset.size()) {
    throw InputError(s.name + ": the images have " + std::to_string(s.frames->size()) +
                     " frames, the poses " + std::to_string(dataset.size()));
  }
  for (std::size_t i = 0; i < dataset.size(); ++i) {
    const FrameStamp stamp = dataset.stamp(i);
    s.frame_timestamps_s.push_back(stamp.timestamp_s);
    s.frame_T_S_C.push_back(stamp.T_W_C);
    s.keyframes.push_back(i);
  }
  return s;
}

}  // namespace strata::align
