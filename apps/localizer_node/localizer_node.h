#pragma once
// strata-localizer's LCM side. Handlers are thin: decode (never trusting the payload), hand to
// plain C++ (FrameAssembler, LocalizerCore), publish. Two threads: the receive thread turns every
// odometry pose into a map-frame pose at once (the output keeps the odometry's rate) and pairs
// frames with their odometry pose; the caller's thread localises, one frame at a time, the
// newest frame offered (a one-frame slot: a frame offered while the slot is full replaces the one
// waiting there, counted as skipped busy), and applies each localisation to the correction the
// next pose goes out with.
// Frames: colour + depth as strata-mapper takes them (rgbd_frame_t with camera_info_t); a pose
// inside a frame is ignored (the odometry's poses are the ones the map is corrected from).
// Output: pose_t T_W_C (parent "world": the prior map's frame, which strata-mapper accepts) for
// every odometry pose once initialised, with the correction's covariance ((t, r) in map axes
// about the camera centre, standing in for pose_t's (x, y, z, roll, pitch, yaw)); one
// localization_status_t per frame paired with an odometry pose.
// Bad input never stops the node: it is counted (LocalizerCounters) and logged (the first 10 per
// channel, then every 1000th).
// Thread safety: run() once; snapshot() from any thread.
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <lcm/lcm-cpp.hpp>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "localizer_node/localizer_core.h"
#include "localizer_node/localizer_options.h"
#include "localizer_node/localizer_report.h"
#include "strata/lcm/frame_assembler.h"
#include "strata/lcm/input_stats.h"
#include "strata/localization_status_t.hpp"

namespace strata::apps {

class LocalizerNode {
 public:
  /// Subscribes on `input`, publishes on `output` (may be the same object); all must outlive it.
  /// Throws InputError for an LCM that is not good.
  LocalizerNode(lcm::LCM& input, lcm::LCM& output, LocalizerCore& core,
                const LocalizerOptions& options);
  ~LocalizerNode();
  LocalizerNode(const LocalizerNode&) = delete;
  LocalizerNode& operator=(const LocalizerNode&) = delete;

  /// Receives and localises until `stop` is set or, with options.max_idle_s, until no frame or
  /// odometry message came for that long; then localises the frame still waiting in the slot.
  /// Returns the final state (stopped_by "signal" or "idle").
  LocalizerSnapshot run(const std::atomic<bool>& stop);

  LocalizerSnapshot snapshot(const std::string& stopped_by = "") const;

 private:
  using Clock = std::chrono::steady_clock;
  struct SlotFrame {
    lcm_io::ReadyFrame ready;  // frame.T_W_C: its odometry pose T_O_C
    Clock::time_point offered;
  };

  void receiveLoop();
  void onFrame(const lcm::ReceiveBuffer* buffer, const std::string& channel);
  void onOdometry(const lcm::ReceiveBuffer* buffer, const std::string& channel);
  void onCameraInfo(const lcm::ReceiveBuffer* buffer, const std::string& channel);
  void offerReady(lcm_io::AssemblerOutput out);
  bool idle() const;

  void localizeOne(const SlotFrame& slot);
  void publishPose(const localize::FusedPose& fused, std::int64_t utime,
                   const std::string& child_frame);
  void publishStatus(const localization_status_t& status);
  localization_status_t skippedStatus(std::int64_t frame_utime, const std::string& reason) const;
  void reportIfDue(bool force);
  void log(const std::string& line) const;

  lcm::LCM& input_;
  lcm::LCM& output_;
  LocalizerCore& core_;
  LocalizerOptions options_;
  std::vector<lcm::Subscription*> subscriptions_;
  lcm_io::InputStats input_stats_;
  std::atomic<bool> receiving_{false};
  const Clock::time_point started_;
  std::atomic<Clock::rep> last_input_;  // time of the last frame or odometry message

  // Receive thread only.
  lcm_io::FrameAssembler assembler_;
  std::int64_t gaps_logged_ = 0, no_pose_logged_ = 0;

  mutable std::mutex mutex_;  // guards the members below
  std::condition_variable slot_ready_;
  std::optional<SlotFrame> slot_;
  LocalizerCounters counters_;
  localize::FusedPose last_fused_;  // after the last odometry pose or correction
  std::vector<double> localize_ms_, latency_ms_;
  std::optional<Clock::time_point> first_pose_, last_pose_;
  std::string last_reason_;
  std::mutex publish_mutex_;  // one publisher at a time on output_

  // Worker thread only.
  Clock::time_point next_report_;
};

}  // namespace strata::apps
