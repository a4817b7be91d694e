#include "localizer_node/localizer_report.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <nlohmann/json.hpp>

#include "strata/core/statistics.h"

namespace strata::apps {
namespace {

using Json = nlohmann::ordered_json;

double fraction(std::int64_t part, std::int64_t whole) {
  return whole > 0 ? static_cast<double>(part) / static_cast<double>(whole) : 0.0;
}

double posesPerSecond(const LocalizerSnapshot& s) {
  return s.pose_span_s > 0.0 ? static_cast<double>(s.counters.poses_published - 1) / s.pose_span_s
                             : 0.0;
}

/// The interpolated q-quantile of the times, 0 when there are none (nothing timed yet).
double timeQuantile(const std::vector<double>& ms, double q) {
  return ms.empty() ? 0.0 : quantile(ms, q);
}

Json timingJson(const std::vector<double>& ms) {
  Json j;
  j["count"] = ms.size();
  j["median_ms"] = timeQuantile(ms, 0.5);
  j["p90_ms"] = timeQuantile(ms, 0.9);
  j["max_ms"] = ms.empty() ? 0.0 : *std::max_element(ms.begin(), ms.end());
  return j;
}

}  // namespace

std::string localizerStatusLine(const LocalizerSnapshot& s) {
  const LocalizerCounters& c = s.counters;
  char line[512];
  std::snprintf(
      line, sizeof(line),
      "strata-localizer: %lld frames in, %lld tried, %lld localised, %lld skipped "
      "(%lld busy); %lld corrections accepted, %lld rejected; %s; %lld poses out",
      static_cast<long long>(c.frames_received), static_cast<long long>(c.frames_attempted),
      static_cast<long long>(c.frames_localized),
      static_cast<long long>(c.frames_skipped_every + c.frames_skipped_busy),
      static_cast<long long>(c.frames_skipped_busy), static_cast<long long>(s.corrections_accepted),
      static_cast<long long>(s.corrections_rejected),
      s.initialised ? "tracking in the map frame" : "not initialised",
      static_cast<long long>(c.poses_published));
  std::string text = line;
  if (!s.initialised && !s.last_reason.empty()) text += " (last: " + s.last_reason + ")";
  return text;
}

std::string localizerSummary(const LocalizerSnapshot& s) {
  const LocalizerCounters& c = s.counters;
  char text[1024];
  std::snprintf(
      text, sizeof(text),
      "strata-localizer: stopped by %s after %.1f s: %lld frames received (%lld rejected, %lld "
      "without odometry), %lld tried, %lld localised (%.0f %%), %lld skipped by --every, %lld "
      "while busy; corrections %lld accepted, %lld rejected.\n"
      "strata-localizer: odometry %lld poses in, %lld refused, %lld gaps; %lld map-frame poses "
      "out (%.1f per s), %lld before initialisation.\n"
      "strata-localizer: localisation %.0f ms median, %.0f ms p90; frame to correction %.0f ms "
      "median, %.0f ms p90.\n",
      s.stopped_by.c_str(), s.elapsed_s, static_cast<long long>(c.frames_received),
      static_cast<long long>(c.frames_rejected), static_cast<long long>(c.frames_dropped_no_pose),
      static_cast<long long>(c.frames_attempted), static_cast<long long>(c.frames_localized),
      100.0 * fraction(c.frames_localized, c.frames_attempted),
      static_cast<long long>(c.frames_skipped_every), static_cast<long long>(c.frames_skipped_busy),
      static_cast<long long>(s.corrections_accepted),
      static_cast<long long>(s.corrections_rejected), static_cast<long long>(c.odometry_received),
      static_cast<long long>(c.odometry_refused), static_cast<long long>(c.odometry_gaps),
      static_cast<long long>(c.poses_published), posesPerSecond(s),
      static_cast<long long>(c.poses_uninitialised), timeQuantile(s.localize_ms, 0.5),
      timeQuantile(s.localize_ms, 0.9), timeQuantile(s.latency_ms, 0.5),
      timeQuantile(s.latency_ms, 0.9));
  return text;
}

std::string localizerReportJson(const LocalizerSnapshot& s, const std::string& db_path, int every,
                                std::size_t map_keyframes) {
  const LocalizerCounters& c = s.counters;
  Json j;
  j["db"] = db_path;
  j["map_keyframes"] = map_keyframes;
  j["every"] = every;
  j["stopped_by"] = s.stopped_by;
  j["elapsed_s"] = s.elapsed_s;
  j["initialised"] = s.initialised;
  Json frames;
  frames["received"] = c.frames_received;
  frames["rejected"] = c.frames_rejected;
  frames["dropped_no_pose"] = c.frames_dropped_no_pose;
  frames["ready"] = c.frames_ready;
  frames["skipped_every"] = c.frames_skipped_every;
  frames["skipped_busy"] = c.frames_skipped_busy;
  frames["attempted"] = c.frames_attempted;
  frames["localized"] = c.frames_localized;
  frames["localized_fraction"] = fraction(c.frames_localized, c.frames_attempted);
  j["frames"] = frames;
  j["corrections_accepted"] = s.corrections_accepted;
  j["corrections_rejected"] = s.corrections_rejected;
  Json odometry;
  odometry["received"] = c.odometry_received;
  odometry["refused"] = c.odometry_refused;
  odometry["gaps"] = c.odometry_gaps;
  j["odometry"] = odometry;
  Json poses;
  poses["published"] = c.poses_published;
  poses["before_initialisation"] = c.poses_uninitialised;
  poses["per_s"] = posesPerSecond(s);
  j["poses"] = poses;
  j["messages_unpublished"] = c.messages_unpublished;
  j["localize"] = timingJson(s.localize_ms);
  j["latency"] = timingJson(s.latency_ms);
  j["last_reason"] = s.last_reason;
  return j.dump(2, ' ', false, Json::error_handler_t::replace) + "\n";
}

}  // namespace strata::apps
