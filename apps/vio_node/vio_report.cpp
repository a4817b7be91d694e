#include "vio_node/vio_report.h"

#include <algorithm>
#include <cstdio>
#include <sstream>

#include "core/json_text.h"

namespace strata::apps {
namespace {

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
                                   s.pipeline.imu_out_of_order_skipped);
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

std::string vioSummaryJson(const VioSnapshot& s, const std::string& calibration_dir) {
  const odometry::PipelineStats& p = s.pipeline;
  const VioCounters& c = s.counters;
  const double processed = static_cast<double>(std::max<std::size_t>(1, p.frames_processed));
  std::ostringstream j;
  j << "{\"calibration\": " << jsonQuoted(calibration_dir)
    << ", \"stereo\": " << (s.stereo ? "true" : "false")
    << ", \"stopped_by\": " << jsonQuoted(s.stopped_by)
    << ", \"elapsed_s\": " << jsonNumber(s.elapsed_s)
    << ", \"frames_received\": " << c.frames_received
    << ", \"frames_processed\": " << p.frames_processed
    << ", \"frames_tracked\": " << p.frames_tracking
    << ", \"frames_initializing\": " << p.frames_initializing << ", \"failures\": " << p.failures
    << ", \"poses_published\": " << c.poses_published
    << ", \"poses_unpublished\": " << c.poses_unpublished << ", \"first_tracked_utime\": "
    << (p.first_tracking_ns >= 0 ? std::to_string(p.first_tracking_ns / 1000) : "null")
    << ", \"last_failure\": " << jsonQuoted(s.last_failure) << ", \"failure_log\": [";
  for (std::size_t i = 0; i < p.failure_log.size(); ++i) {
    j << (i ? ", " : "") << "{\"utime\": " << p.failure_log[i].first / 1000
      << ", \"reason\": " << jsonQuoted(p.failure_log[i].second) << "}";
  }
  j << "], \"frames_skipped\": {\"corrupt\": " << c.frames_corrupt
    << ", \"bad_image\": " << c.frames_bad_image
    << ", \"out_of_order\": " << p.frames_out_of_order_skipped
    << ", \"without_imu\": " << p.frames_without_imu_skipped
    << ", \"backlog\": " << c.frames_dropped_backlog << "}"
    << ", \"imu_received\": " << c.imu_received << ", \"imu_accepted\": " << p.imu_samples
    << ", \"imu_skipped\": {\"corrupt\": " << c.imu_corrupt
    << ", \"nonfinite\": " << c.imu_nonfinite + static_cast<std::int64_t>(p.imu_nonfinite_skipped)
    << ", \"out_of_order\": " << p.imu_out_of_order_skipped
    << ", \"backlog\": " << c.imu_dropped_backlog << "}"
    << ", \"frontend_ms_per_frame\": " << jsonNumber(p.frontend_ms_total / processed)
    << ", \"backend_ms_per_frame\": " << jsonNumber(p.backend_ms_total / processed) << "}\n";
  return j.str();
}

}  // namespace strata::apps
