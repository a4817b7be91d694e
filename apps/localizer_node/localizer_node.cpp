// LocalizerNode, receive side: subscriptions, the handlers of the input channels, map-frame poses
// at the odometry's rate, frames offered to the localiser.
#include "localizer_node/localizer_node.h"

#include <cstdio>
#include <exception>
#include <thread>

#include "strata/camera_info_t.hpp"
#include "strata/core/error.h"
#include "strata/lcm/convert_frame.h"
#include "strata/lcm/convert_pose.h"
#include "strata/lcm/lcm_time.h"
#include "strata/lcm/receive_loop.h"
#include "strata/pose_t.hpp"
#include "strata/rgbd_frame_t.hpp"

namespace strata::apps {
namespace {

constexpr int kReceiveTimeoutMs = 50;

/// Runs `handle`; bad input is counted on `channel` (with `on_bad` for the node's own counters)
/// and logged, never thrown into LCM's dispatch.
template <typename Handle, typename OnBad>
void guarded(lcm_io::InputStats& stats, const std::string& channel, Handle handle, OnBad on_bad) {
  try {
    handle();
  } catch (const InputError& e) {
    stats.countBad(channel, e.what());
    on_bad();
  } catch (const std::exception& e) {  // e.g. bad_alloc from a huge valid message
    stats.countBad(channel, std::string("unexpected: ") + e.what());
    on_bad();
  }
}

/// Frames wait for the odometry pose after them no longer than the odometry may pause.
lcm_io::AssemblerConfig assemblerConfig(const LocalizerOptions& options) {
  lcm_io::AssemblerConfig config;
  config.max_pose_gap_us = static_cast<std::int64_t>(options.max_odometry_gap_s * 1e6);
  return config;
}

}  // namespace

LocalizerNode::LocalizerNode(lcm::LCM& input, lcm::LCM& output, LocalizerCore& core,
                             const LocalizerOptions& options)
    : input_(input),
      output_(output),
      core_(core),
      options_(options),
      input_stats_("strata-localizer"),
      started_(Clock::now()),
      last_input_(Clock::now().time_since_epoch().count()),
      assembler_(assemblerConfig(options)),
      next_report_(started_ + std::chrono::duration_cast<Clock::duration>(
                                  std::chrono::duration<double>(options.status_period_s))) {
  if (!input_.good()) throw InputError("LCM input '" + options.url + "' could not be opened");
  if (!output_.good()) throw InputError("LCM output could not be opened");
  const LocalizerChannels& c = options_.channels;
  subscriptions_.push_back(input_.subscribe(c.rgbd, &LocalizerNode::onFrame, this));
  subscriptions_.push_back(input_.subscribe(c.odometry, &LocalizerNode::onOdometry, this));
  subscriptions_.push_back(input_.subscribe(c.camera_info, &LocalizerNode::onCameraInfo, this));
}

LocalizerNode::~LocalizerNode() {
  for (lcm::Subscription* s : subscriptions_) input_.unsubscribe(s);
}

void LocalizerNode::receiveLoop() {
  // NOTE: the input stops e.g. at the end of a log file (file:// provider): keep localising what is
  // offered.
  lcm_io::receiveUntilStopped(input_, receiving_, kReceiveTimeoutMs, [this] {
    log("LCM input stopped delivering messages (end of log or socket error)");
  });
}

void LocalizerNode::onFrame(const lcm::ReceiveBuffer* buffer, const std::string& channel) {
  last_input_ = Clock::now().time_since_epoch().count();
  {
    std::lock_guard<std::mutex> lock(mutex_);
    ++counters_.frames_received;
  }
  guarded(
      input_stats_, channel,
      [&] {
        rgbd_frame_t message;
        lcm_io::decodePayload(buffer->data, static_cast<int>(buffer->data_size), message);
        lcm_io::ReceivedFrame received = lcm_io::decodeFrame(message);
        received.has_pose = false;  // the odometry's pose, not the sender's
        offerReady(assembler_.onFrame(std::move(received)));
      },
      [&] {
        std::lock_guard<std::mutex> lock(mutex_);
        ++counters_.frames_rejected;
      });
}

void LocalizerNode::onOdometry(const lcm::ReceiveBuffer* buffer, const std::string& channel) {
  last_input_ = Clock::now().time_since_epoch().count();
  {
    std::lock_guard<std::mutex> lock(mutex_);
    ++counters_.odometry_received;
  }
  guarded(
      input_stats_, channel,
      [&] {
        pose_t message;
        lcm_io::decodePayload(buffer->data, static_cast<int>(buffer->data_size), message);
        const Eigen::Isometry3d T_O_C = lcm_io::decodePose(message);
        double gap_s = 0.0;
        const localize::FusedPose fused = core_.odometry(message.utime, T_O_C, &gap_s);
        if (gap_s > options_.max_odometry_gap_s) {
          {
            std::lock_guard<std::mutex> lock(mutex_);
            ++counters_.odometry_gaps;
          }
          if (++gaps_logged_ <= 10 || gaps_logged_ % 100 == 0) {
            char line[160];
            std::snprintf(line, sizeof(line),
                          "odometry gap of %.2f s before utime %lld (frames inside it get no "
                          "pose; counted)",
                          gap_s, static_cast<long long>(message.utime));
            log(line);
          }
        }
        publishPose(fused, message.utime, message.child_frame);
        // The core refused stamps out of order already, so the assembler takes this one.
        offerReady(assembler_.onPose(message.utime, T_O_C));
      },
      [&] {
        std::lock_guard<std::mutex> lock(mutex_);
        ++counters_.odometry_refused;
      });
}

void LocalizerNode::onCameraInfo(const lcm::ReceiveBuffer* buffer, const std::string& channel) {
  guarded(
      input_stats_, channel,
      [&] {
        camera_info_t message;
        lcm_io::decodePayload(buffer->data, static_cast<int>(buffer->data_size), message);
        assembler_.onCameraInfo(message.camera_id, lcm_io::decodeCameraInfo(message));
      },
      [] {});
}

void LocalizerNode::offerReady(lcm_io::AssemblerOutput out) {
  for (const std::string& reason : out.drop_reasons) {
    if (++no_pose_logged_ <= 10 || no_pose_logged_ % 100 == 0) log(reason);
  }
  std::vector<localization_status_t> skipped;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    counters_.frames_dropped_no_pose += static_cast<std::int64_t>(out.dropped_no_pose);
    for (lcm_io::ReadyFrame& frame : out.ready) {
      const std::int64_t index = counters_.frames_ready++;
      if (index % options_.every != 0) {
        ++counters_.frames_skipped_every;
        skipped.push_back(skippedStatus(frame.utime, "skipped: not an --every'th frame"));
        continue;
      }
      if (slot_) {
        ++counters_.frames_skipped_busy;
        skipped.push_back(skippedStatus(slot_->ready.utime,
                                        "skipped: the localiser was busy and a newer frame came"));
      }
      slot_ = SlotFrame{std::move(frame), Clock::now()};
    }
  }
  slot_ready_.notify_one();
  for (const localization_status_t& status : skipped) publishStatus(status);
}

localization_status_t LocalizerNode::skippedStatus(std::int64_t frame_utime,
                                                   const std::string& reason) const {
  localization_status_t s{};
  s.utime = lcm_io::nowUtime();
  s.frame_utime = frame_utime;
  s.status = last_fused_.status == localize::FusionStatus::kUninitialised
                 ? localization_status_t::UNINITIALISED
                 : localization_status_t::TRACKING;
  s.attempted = false;
  s.localized = false;
  s.reason = reason;
  s.sigma_m = static_cast<float>(last_fused_.translation_sigma_m);
  return s;
}

bool LocalizerNode::idle() const {
  if (options_.max_idle_s <= 0.0) return false;
  const Clock::time_point last{Clock::duration(last_input_.load())};
  return std::chrono::duration<double>(Clock::now() - last).count() > options_.max_idle_s;
}

void LocalizerNode::log(const std::string& line) const {
  std::fprintf(stderr, "strata-localizer: %s\n", line.c_str());
}

}  // namespace strata::apps
