// VioNode, worker side: the VIO on the queued messages, pose publishing, progress reports.
#include <cstdio>
#include <thread>

#include "strata/core/error.h"
#include "strata/lcm/convert_pose.h"
#include "vio_node/vio_node.h"

namespace strata::apps {
namespace {

constexpr std::chrono::milliseconds kQueueWait{100};

}  // namespace

VioSnapshot VioNode::run(const std::atomic<bool>& stop) {
  receiving_ = true;
  std::thread receiver([this] { receiveLoop(); });
  std::string stopped_by;
  while (stopped_by.empty()) {
    if (const auto item = queue_.pop(kQueueWait)) process(*item);
    reportIfDue(false);
    if (stop)
      stopped_by = "signal";
    else if (queue_.empty() && idle())
      stopped_by = "idle";
  }
  receiving_ = false;
  receiver.join();
  // NOTE: what was received before the stop is still processed (at most --queue frames).
  while (const auto item = queue_.pop(std::chrono::milliseconds(0))) process(*item);
  core_.flush();
  reportIfDue(true);
  return snapshot(stopped_by);
}

void VioNode::process(const SensorQueue::Item& item) {
  if (const auto* imu = std::get_if<lcm_io::ImuMsg>(&item)) {
    publish(core_.onImu(*imu));
    return;
  }
  try {
    publish(core_.onFrame(std::get<lcm_io::StereoFrameMsg>(item)));
  } catch (const InputError& e) {  // images the calibration does not describe
    input_stats_.countBad(options_.channels.stereo, e.what());
    std::lock_guard<std::mutex> lock(mutex_);
    ++counters_.frames_bad_image;
  }
}

void VioNode::publish(const std::vector<VioPose>& poses) {
  for (const VioPose& pose : poses) {
    const pose_t message =
        lcm_io::encodePose(pose.T_W_C, pose.utime, lcm_io::kWorldFrame, left_camera_);
    const bool sent = output_.publish(options_.channels.pose, &message) == 0;
    std::lock_guard<std::mutex> lock(mutex_);
    if (sent) {
      ++counters_.poses_published;
    } else if (++counters_.poses_unpublished == 1) {
      std::fprintf(stderr, "strata-vio: LCM refused to publish a pose on %s (counted)\n",
                   options_.channels.pose.c_str());
    }
  }
}

VioSnapshot VioNode::snapshot(const std::string& stopped_by) const {
  VioSnapshot s;
  s.counters = counters();
  s.pipeline = core_.stats();
  s.stereo = core_.stereo();
  s.last_failure = core_.lastFailure();
  s.initialising_reason = core_.initialisingReason();
  s.elapsed_s = std::chrono::duration<double>(Clock::now() - started_).count();
  s.stopped_by = stopped_by;
  return s;
}

void VioNode::reportIfDue(bool force) {
  if (options_.quiet || options_.status_period_s <= 0.0) return;
  const Clock::time_point now = Clock::now();
  if (!force && now < next_report_) return;
  const std::size_t processed = core_.stats().frames_processed;
  const double period_s = std::chrono::duration<double>(now - last_report_).count();
  const double frames_per_s =
      period_s > 0.0 ? static_cast<double>(processed - frames_at_report_) / period_s : 0.0;
  std::fprintf(stderr, "%s\n", vioStatusLine(snapshot(""), frames_per_s).c_str());
  frames_at_report_ = processed;
  last_report_ = now;
  next_report_ = now + std::chrono::duration_cast<Clock::duration>(
                           std::chrono::duration<double>(options_.status_period_s));
}

}  // namespace strata::apps
