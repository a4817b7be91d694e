#pragma once
// What strata-localizer tells about its run: counters of every kind of input it took, skipped or
// refused, how many frames were localised and how long that took, as a one-line progress report
// (stderr), the summary printed at exit, and a JSON report.
#include <cstdint>
#include <string>
#include <vector>

namespace strata::apps {

/// Messages and frames counted by kind. Frames: received = rejected + dropped without a pose +
/// ready (+ still waiting for an odometry pose); ready = skipped by --every + skipped busy +
/// attempted (+ one waiting in the slot).
struct LocalizerCounters {
  std::int64_t frames_received = 0;         // messages on the frame channel
  std::int64_t frames_rejected = 0;         // undecodable, no camera info, sizes, stamp order
  std::int64_t frames_dropped_no_pose = 0;  // no odometry around them (gap, too old, backlog)
  std::int64_t frames_ready = 0;            // with an odometry pose
  std::int64_t frames_skipped_every = 0;    // not the --every'th frame
  std::int64_t frames_skipped_busy = 0;     // replaced in the slot by a newer frame
  std::int64_t frames_attempted = 0;        // localisation ran
  std::int64_t frames_localized = 0;        // of those, a pose in the map was found
  std::int64_t odometry_received = 0;       // messages on the odometry channel
  std::int64_t odometry_refused = 0;        // undecodable, non-finite, time backwards or repeated
  std::int64_t odometry_gaps = 0;           // accepted after more than --max-odometry-gap
  std::int64_t poses_published = 0;         // map-frame poses
  std::int64_t poses_uninitialised = 0;     // odometry poses before the first correction: none out
  std::int64_t messages_unpublished = 0;    // LCM refused to send
};

/// The state of a run at one moment.
struct LocalizerSnapshot {
  LocalizerCounters counters;
  std::int64_t corrections_accepted = 0;  // localisations the fusion took (initialisation too)
  std::int64_t corrections_rejected = 0;  // gated out
  bool initialised = false;
  std::vector<double> localize_ms;  // per attempted frame: wall time of the localisation
  std::vector<double> latency_ms;   // per attempted frame: frame ready -> correction done
  double pose_span_s = 0.0;         // first to last map-frame pose published
  double elapsed_s = 0.0;           // since the node started
  std::string last_reason;          // why the last tried frame was not localised or not accepted
  std::string stopped_by;           // "signal" or "idle" once stopped, else ""
};


/// One line: frames in, tried, localised, skipped; corrections; poses out.
std::string localizerStatusLine(const LocalizerSnapshot& s);
/// The lines printed at exit: counts, localised fraction, poses out per second, timings.
std::string localizerSummary(const LocalizerSnapshot& s);
/// The summary as JSON text (ends with a newline).
std::string localizerReportJson(const LocalizerSnapshot& s, const std::string& db_path, int every,
                                std::size_t map_keyframes);

}  // namespace strata::apps
