// LocalizerNode, worker side: the localiser on the slot's frame, corrections, publishing, progress
// reports and the orderly stop.
#include <cstdio>
#include <thread>

#include "localizer_node/localizer_node.h"
#include "strata/core/error.h"
#include "strata/lcm/convert_pose.h"
#include "strata/lcm/lcm_time.h"

namespace strata::apps {
namespace {

constexpr std::chrono::milliseconds kSlotWait{100};

double msBetween(std::chrono::steady_clock::time_point a, std::chrono::steady_clock::time_point b) {
  return std::chrono::duration<double, std::milli>(b - a).count();
}

std::int8_t statusCode(localize::FusionStatus status) {
  switch (status) {
    case localize::FusionStatus::kUninitialised:
      return localization_status_t::UNINITIALISED;
    case localize::FusionStatus::kTracking:
      return localization_status_t::TRACKING;
    case localize::FusionStatus::kCorrected:
      return localization_status_t::CORRECTED;
  }
  return localization_status_t::UNINITIALISED;
}

}  // namespace

LocalizerSnapshot LocalizerNode::run(const std::atomic<bool>& stop) {
  receiving_ = true;
  std::thread receiver([this] { receiveLoop(); });
  std::string stopped_by;
  try {
    while (stopped_by.empty()) {
      std::optional<SlotFrame> frame;
      {
        std::unique_lock<std::mutex> lock(mutex_);
        slot_ready_.wait_for(lock, kSlotWait, [this] { return slot_.has_value(); });
        frame.swap(slot_);
      }
      if (frame) localizeOne(*frame);
      reportIfDue(false);
      if (stop) {
        stopped_by = "signal";
      } else if (idle()) {
        std::lock_guard<std::mutex> lock(mutex_);
        if (!slot_) stopped_by = "idle";
      }
    }
  } catch (...) {
    receiving_ = false;  // never leave the receive thread running behind an exception
    receiver.join();
    throw;
  }
  receiving_ = false;
  receiver.join();
  // NOTE: the frame still waiting was received before the stop: localise it too.
  std::optional<SlotFrame> last;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    last.swap(slot_);
  }
  if (last) localizeOne(*last);
  reportIfDue(true);
  return snapshot(stopped_by);
}

void LocalizerNode::localizeOne(const SlotFrame& slot) {
  const Clock::time_point start = Clock::now();
  const Eigen::Isometry3d& T_O_C = slot.ready.frame.T_W_C;
  localize::Localization l;
  try {
    l = core_.localize(slot.ready, core_.priorFor(T_O_C));
  } catch (const std::exception& e) {  // images the intrinsics do not describe
    input_stats_.countBad(options_.channels.rgbd, e.what());
    std::lock_guard<std::mutex> lock(mutex_);
    ++counters_.frames_rejected;
    return;
  }
  const localize::FusedPose fused = core_.correct(l, T_O_C);
  const Clock::time_point done = Clock::now();
  localization_status_t s{};
  s.utime = lcm_io::nowUtime();
  s.frame_utime = slot.ready.utime;
  s.status = statusCode(fused.status);
  s.attempted = true;
  s.localized = l.localized;
  s.reason = l.localized ? fused.note : l.reason;
  if (s.reason == "initialised") s.reason = "";  // accepted: nothing to explain
  s.candidates = static_cast<std::int32_t>(l.candidates);
  s.accepted = static_cast<std::int32_t>(l.accepted);
  s.inliers = l.inliers;
  s.sigma_m = static_cast<float>(fused.translation_sigma_m);
  s.jump_m = static_cast<float>(fused.jump_m);
  s.localize_ms = static_cast<float>(l.time_ms > 0.0 ? l.time_ms : msBetween(start, done));
  s.latency_ms = static_cast<float>(msBetween(slot.offered, done));
  {
    std::lock_guard<std::mutex> lock(mutex_);
    ++counters_.frames_attempted;
    if (l.localized) ++counters_.frames_localized;
    localize_ms_.push_back(s.localize_ms);
    latency_ms_.push_back(s.latency_ms);
    if (!s.reason.empty()) last_reason_ = s.reason;
    last_fused_ = fused;
  }
  publishStatus(s);
}

void LocalizerNode::publishPose(const localize::FusedPose& fused, std::int64_t utime,
                                const std::string& child_frame) {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    last_fused_ = fused;
    if (fused.status == localize::FusionStatus::kUninitialised) {
      ++counters_.poses_uninitialised;
      return;
    }
  }
  pose_t message = lcm_io::encodePose(fused.T_W_C, utime, lcm_io::kWorldFrame,
                                      child_frame.empty() ? lcm_io::kCameraFrame : child_frame);
  for (int r = 0; r < 6; ++r) {
    for (int c = 0; c < 6; ++c) message.covariance[6 * r + c] = fused.covariance(r, c);
  }
  bool sent = false;
  {
    std::lock_guard<std::mutex> lock(publish_mutex_);
    sent = output_.publish(options_.channels.pose, &message) == 0;
  }
  std::lock_guard<std::mutex> lock(mutex_);
  if (!sent) {
    if (++counters_.messages_unpublished == 1)
      log("LCM refused to publish on " + options_.channels.pose + " (counted)");
    return;
  }
  ++counters_.poses_published;
  const Clock::time_point now = Clock::now();
  if (!first_pose_) first_pose_ = now;
  last_pose_ = now;
}

void LocalizerNode::publishStatus(const localization_status_t& status) {
  bool sent = false;
  {
    std::lock_guard<std::mutex> lock(publish_mutex_);
    sent = output_.publish(options_.channels.status, &status) == 0;
  }
  if (sent) return;
  std::lock_guard<std::mutex> lock(mutex_);
  if (++counters_.messages_unpublished == 1)
    log("LCM refused to publish on " + options_.channels.status + " (counted)");
}

LocalizerSnapshot LocalizerNode::snapshot(const std::string& stopped_by) const {
  LocalizerSnapshot s;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    s.counters = counters_;
    s.localize_ms = localize_ms_;
    s.latency_ms = latency_ms_;
    if (first_pose_)
      s.pose_span_s = std::chrono::duration<double>(*last_pose_ - *first_pose_).count();
    s.last_reason = last_reason_;
  }
  s.corrections_accepted = static_cast<std::int64_t>(core_.accepted());
  s.corrections_rejected = static_cast<std::int64_t>(core_.rejected());
  s.initialised = core_.initialised();
  s.elapsed_s = std::chrono::duration<double>(Clock::now() - started_).count();
  s.stopped_by = stopped_by;
  return s;
}

void LocalizerNode::reportIfDue(bool force) {
  if (options_.quiet || options_.status_period_s <= 0.0) return;
  const Clock::time_point now = Clock::now();
  if (!force && now < next_report_) return;
  std::fprintf(stderr, "%s\n", localizerStatusLine(snapshot()).c_str());
  next_report_ = now + std::chrono::duration_cast<Clock::duration>(
                           std::chrono::duration<double>(options_.status_period_s));
}

}  // namespace strata::apps
