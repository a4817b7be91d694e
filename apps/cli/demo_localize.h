#pragma once
// `strata demo --localize`: teach once, repeat many times, with no truth poses anywhere. Session 0
// is the teach: its drifting odometry, in a frame of its own, is the map frame, and its frames
// are the prior map's keyframes (localize/prior_map.h). Every later session is a repeat: its own
// drifting odometry, in a frame of its own, fused with localisations of each of its frames
// against that map (localize/session_localization.h), and fused for change detection on the
// fused map-frame poses; frames the fusion could not place yet are left out. For scoring against
// the world's truth the map frame is taken into the truth's world by session 0's true odometry
// frame (one transform for all sessions: the teach's drift stays in the map, as it would).
#include <memory>
#include <string>
#include <vector>

#include "strata/sim/session/sim_session.h"

namespace strata::apps {

struct DemoLocalizeSession {
  std::string name;
  std::size_t frames = 0, attempted = 0, localized = 0, placed = 0, rejected = 0;
  std::size_t wrong = 0;              // placed frames > 0.5 m or 10 degrees from the truth
  double median_error_m = 0.0, max_error_m = 0.0;
  double odometry_max_error_m = 0.0;  // the session's odometry alone, placed by its first pose
  double median_localization_ms = 0.0;
};

struct DemoLocalizeResult {
  std::size_t map_keyframes = 0;
  std::vector<DemoLocalizeSession> sessions;  // the repeats (sessions 1...)
  double localize_s = 0.0;                    // map building and localisation, wall time
};

/// Moves the sessions' drifted given poses into frames of their own, builds the map from session
/// 0, localises the others against it and replaces their given poses as described above.
DemoLocalizeResult useLocalizedPoses(
    const std::vector<std::shared_ptr<sim::SimSessionDataset>>& sessions, bool quiet);

std::string demoLocalizeJson(const DemoLocalizeResult& result);
std::string summarizeDemoLocalize(const DemoLocalizeResult& result);

}  // namespace strata::apps
