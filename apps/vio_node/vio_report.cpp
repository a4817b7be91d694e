#include "vio_node/vio_report.h"

#include <algorithm>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <sstream>

namespace strata::apps {
namespace {

using Json = nlohmann::ordered_json;

std::int64_t framesSkipped(const VioSnapshot& s) {
  const VioCounters& c = s.counters;
  return c.frames_corrupt + c.frames_bad_image + c.frames_dropped_backlog +
         static_cast<std::int64_t>(s.pipeline.frames_out_of_order_skipped +
                                   s.pipeline.frames_without_imu_skipped);
}

std::int64_t imuSkipped(const VioSnapshot& s) {
  const VioCounters& c = s.counters;
  return c.imu_corrupt + c.imu_nonfinite + c.imu_dropped_backlog +
         static_cast<std::int64_t>(s.pipeline.imu_nonfinite_skipped +
                                   s.pipeline.imu_out_of_range_skipped +
                                   s.pipeline.imu_out_of_order_skipped);
}

/// The failures as {"utime", "reason"}, oldest first.
Json failureLogJson(const odometry::PipelineStats& p) {
  Json log = Json::array();
  for (const auto& [t_ns, reason] : p.failure_log) {
    Json j;
    j["utime"] = t_ns / 1000;
    j["reason"] = reason;
    log.push_back(std::move(j));
  }
  return log;
}

Json framesSkippedJson(const VioSnapshot& s) {
  Json j;
  j["corrupt"] = s.counters.frames_corrupt;
  j["bad_image"] = s.counters.frames_bad_image;
  j["out_of_order"] = s.pipeline.frames_out_of_order_skipped;
  j["without_imu"] = s.pipeline.frames_without_imu_skipped;
  j["backlog"] = s.counters.frames_dropped_backlog;
  return j;
}

Json imuSkippedJson(const VioSnapshot& s) {
  Json j;
  j["corrupt"] = s.counters.imu_corrupt;
  j["nonfinite"] =
      s.counters.imu_nonfinite + static_cast<std::int64_t>(s.pipeline.imu_nonfinite_skipped);
  j["out_of_range"] = s.pipeline.imu_out_of_range_skipped;
  j["out_of_order"] = s.pipeline.imu_out_of_order_skipped;
  j["backlog"] = s.counters.imu_dropped_backlog;
  return j;
}

}  // namespace

std::string vioStatusLine(const VioSnapshot& s, double frames_per_s) {
  const odometry::PipelineStats& p = s.pipeline;
  std::ostringstream line;
  line << "strata-vio: " << s.counters.frames_received << " frames in, " << p.frames_tracking
       << " tracked, " << p.frames_initializing << " initialising, " << p.failures << " failures";
  if (!s.last_failure.empty()) line << " (last: " << s.last_failure << ")";
  line << ", " << framesSkipped(s) << " frames skipped; IMU " << s.counters.imu_received << " in, "
       << imuSkipped(s) << " skipped; " << s.counters.poses_published << " poses; ";
  char rate[32];
  std::snprintf(rate, sizeof(rate), "%.1f frames/s", frames_per_s);
  line << rate;
  if (p.frames_tracking == 0 && !s.initialising_reason.empty()) {
    line << "; initialising: " << s.initialising_reason;
  }
  return line.str();
}

int vioVerdict(const VioSnapshot& s, std::string* message) {
  const odometry::PipelineStats& p = s.pipeline;
  message->clear();
  if (p.imu_out_of_range_skipped > 0) {
    *message += "strata-vio: " + odometry::imuOutOfRangeWarning(p.imu_out_of_range_skipped) + "\n";
  }
  if (p.frames_processed == 0 || p.frames_tracking > 0) return 0;
  const std::string why = !s.last_failure.empty() ? "the last failure: " + s.last_failure
                          : !s.initialising_reason.empty()
                              ? "never initialised: " + s.initialising_reason
                              : std::string("never initialised");
  *message += "strata-vio: " + std::to_string(p.frames_processed) +
              " frames processed and none tracked (" + why + "); no pose was published\n";
  return 3;
}

std::string vioSummaryJson(const VioSnapshot& s, const std::string& calibration_dir) {
  const odometry::PipelineStats& p = s.pipeline;
  const VioCounters& c = s.counters;
  const double processed = static_cast<double>(std::max<std::size_t>(1, p.frames_processed));
  Json j;
  j["calibration"] = calibration_dir;
  j["stereo"] = s.stereo;
  j["stopped_by"] = s.stopped_by;
  j["elapsed_s"] = s.elapsed_s;
  j["frames_received"] = c.frames_received;
  j["frames_processed"] = p.frames_processed;
  j["frames_tracked"] = p.frames_tracking;
  j["frames_initializing"] = p.frames_initializing;
  j["failures"] = p.failures;
  j["poses_published"] = c.poses_published;
  j["poses_unpublished"] = c.poses_unpublished;
  j["first_tracked_utime"] =
      p.first_tracking_ns >= 0 ? Json(p.first_tracking_ns / 1000) : Json(nullptr);
  j["last_failure"] = s.last_failure;
  j["failure_log"] = failureLogJson(p);
  j["frames_skipped"] = framesSkippedJson(s);
  j["imu_received"] = c.imu_received;
  j["imu_accepted"] = p.imu_samples;
  j["imu_skipped"] = imuSkippedJson(s);
  j["frontend_ms_per_frame"] = p.frontend_ms_total / processed;
  j["backend_ms_per_frame"] = p.backend_ms_total / processed;
  return j.dump(2, ' ', false, Json::error_handler_t::replace) + "\n";
}

}  // namespace strata::apps
