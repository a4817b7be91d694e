#pragma once
// strata-mapper's LCM side. Handlers are thin: decode (never trusting the payload), hand to a
// plain C++ function (FrameAssembler, MapperCore), publish. Two threads: one receives (decode,
// pose lookup, queue with drop-oldest), the caller's fuses and publishes, so a slow frame never
// blocks the socket and a backlog never grows without bound.
// Thread safety: run() once; counters()/stats() from any thread.
#include <atomic>
#include <cstdint>
#include <deque>
#include <lcm/lcm-cpp.hpp>
#include <mutex>
#include <string>
#include <vector>

#include "strata/lcm/frame_assembler.h"
#include "strata/lcm/frame_queue.h"
#include "strata/lcm/input_stats.h"
#include "mapper_node/mapper_core.h"
#include "mapper_node/mapper_options.h"
#include "strata/command_t.hpp"
#include "strata/map_stats_t.hpp"

namespace strata::apps {

struct MapperCounters {
  std::int64_t frames_received = 0;  // messages on the frame channel
  std::int64_t frames_dropped_backlog = 0;
  std::int64_t frames_dropped_no_pose = 0;
  std::int64_t frames_rejected = 0;
  std::int64_t messages_bad = 0;
};

class MapperNode {
 public:
  /// Subscribes on `input`, publishes on `output` (may be the same object). All must outlive it.
  MapperNode(lcm::LCM& input, lcm::LCM& output, MapperCore& core, const MapperOptions& options);
  ~MapperNode();

  /// Receives and fuses until `stop` is set; then fuses the frames still queued, handles queued
  /// commands, publishes a last mesh update and stats, and saves the map to --map when set
  /// (atomically). Returns false when that save failed.
  bool run(const std::atomic<bool>& stop);

  MapperCounters counters() const;
  map_stats_t stats(std::int64_t utime) const;

 private:
  void receiveLoop();
  void onFrame(const lcm::ReceiveBuffer* buffer, const std::string& channel);
  void onPose(const lcm::ReceiveBuffer* buffer, const std::string& channel);
  void onCameraInfo(const lcm::ReceiveBuffer* buffer, const std::string& channel);
  void onCommand(const lcm::ReceiveBuffer* buffer, const std::string& channel);
  void queueReady(lcm_io::AssemblerOutput out);

  void workOnce();
  void fuseOne(const lcm_io::ReadyFrame& frame);
  /// Runs the queued commands whose frames received before them have left the queue (all of
  /// them with `all`).
  void runCommands(bool all = false);
  void runCommand(const command_t& command);
  void publishDue(bool frame_fused);
  /// Saves the map to --map when --save-every has passed since the last save and frames were
  /// fused since (failures are logged; the map and the previous file stay intact).
  void saveDue(double now_s);
  void publishStats();
  void publishMesh(bool full);
  void publishEsdf();
  void publishChangeEvents(const std::vector<change_event_t>& events);
  /// Publishes the object database's updates of a finished session end and saves the database;
  /// with `wait`, waits for one still running first (at exit).
  void publishObjectUpdates(bool wait = false);
  bool saveOnExit();
  void log(const std::string& line) const;

  lcm::LCM& input_;
  lcm::LCM& output_;
  MapperCore& core_;
  MapperOptions options_;
  std::vector<lcm::Subscription*> subscriptions_;
  lcm_io::InputStats input_stats_;
  lcm_io::FrameAssembler assembler_;  // receive thread only
  lcm_io::DropOldestQueue<lcm_io::ReadyFrame> queue_;
  std::atomic<bool> receiving_{false};
  std::uint64_t arrivals_ = 0;        // receive thread: frames and commands queued so far
  std::uint64_t no_pose_logged_ = 0;  // receive thread: frames dropped for want of a pose

  mutable std::mutex mutex_;  // guards the members below
  MapperCounters counters_;
  std::deque<std::pair<std::uint64_t, command_t>> commands_;  // with arrival order
  std::int64_t last_command_id_ = 0;
  std::string last_command_result_;

  // Worker thread only.
  double next_stats_s_ = 0.0, next_mesh_s_ = 0.0, next_esdf_s_ = 0.0, next_save_s_ = 0.0;
  std::int64_t frames_at_last_save_ = 0;
};

/// Commands waiting beyond this are refused (counted as bad on the command channel).
inline constexpr std::size_t kMaxQueuedCommands = 64;

}  // namespace strata::apps
