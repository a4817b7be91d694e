#pragma once
// strata-vio's LCM side. Handlers are thin: decode (never trusting the payload) and queue; the
// VIO (VioCore) runs on the caller's thread and publishes a pose_t per tracked frame. Two threads,
// as in strata-mapper: a slow optimisation step never blocks the socket, whose buffer holds only
// a few stereo pairs.
// Bad input never stops the node: each kind is counted (VioCounters, and the pipeline's own
// counts) and logged (the first 10 per channel, then every 1000th), and no pose is published for
// it.
// Thread safety: run() once; counters() from any thread.
#include <atomic>
#include <chrono>
#include <lcm/lcm-cpp.hpp>
#include <mutex>
#include <string>
#include <vector>

#include "strata/io/euroc_types.h"
#include "strata/lcm/input_stats.h"
#include "vio_node/sensor_queue.h"
#include "vio_node/vio_core.h"
#include "vio_node/vio_options.h"
#include "vio_node/vio_report.h"

namespace strata::apps {

class VioNode {
 public:
  /// Subscribes on `input`, publishes on `output` (may be the same object); both must outlive
  /// it. Throws InputError for an LCM that is not good or a calibration the VIO cannot use.
  VioNode(lcm::LCM& input, lcm::LCM& output, const euroc::Calibration& calibration,
          const VioOptions& options);
  ~VioNode();
  VioNode(const VioNode&) = delete;
  VioNode& operator=(const VioNode&) = delete;

  /// Receives and runs the VIO until `stop` is set or, with options.max_idle_s, until no stereo
  /// or IMU message came for that long; then processes what is queued and drops the frames still
  /// waiting for IMU (counted). Returns the final state (stopped_by "signal" or "idle").
  VioSnapshot run(const std::atomic<bool>& stop);

  VioCounters counters() const;

 private:
  using Clock = std::chrono::steady_clock;

  void receiveLoop();
  void onStereo(const lcm::ReceiveBuffer* buffer, const std::string& channel);
  void onImu(const lcm::ReceiveBuffer* buffer, const std::string& channel);
  void enqueue(SensorQueue::Item item);
  bool idle() const;

  void process(const SensorQueue::Item& item);
  void publish(const std::vector<VioPose>& poses);
  VioSnapshot snapshot(const std::string& stopped_by) const;
  void reportIfDue(bool force);

  lcm::LCM& input_;
  lcm::LCM& output_;
  VioOptions options_;
  std::string left_camera_;  // child frame of the published poses
  std::vector<lcm::Subscription*> subscriptions_;
  lcm_io::InputStats input_stats_;
  SensorQueue queue_;
  std::atomic<bool> receiving_{false};
  const Clock::time_point started_;
  std::atomic<Clock::rep> last_input_;  // time of the last stereo or IMU message

  mutable std::mutex mutex_;  // guards counters_
  VioCounters counters_;

  // Worker thread only.
  VioCore core_;
  Clock::time_point next_report_;
  std::size_t frames_at_report_ = 0;
  Clock::time_point last_report_;
};

}  // namespace strata::apps
