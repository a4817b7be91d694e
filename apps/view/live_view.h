#pragma once
// What strata-view shows: the latest state of a running strata-mapper (and of strata-vio and
// strata-play beside it), kept in a view::Scene from the LCM channels they publish. Read-only:
// nothing is ever published.
//
// Items (view/scene_items.h): every mesh block as "block:x,y,z" (group "map"; a block the mapper
// sends without triangles, or leaves out of a full update, is removed); the camera as "pose"
// (header id "camera": the latest pose of either source below, with the intrinsics of the latest
// camera_info_t when one came); the trajectories "trajectory:map" (the poses inside the frames,
// rgbd_frame_t.has_pose: what the mapper fused at) and "trajectory:vio" (the pose channel: what
// strata-vio, or strata-play --separate-poses, publishes); the objects a session's end found
// (change_event_t: meshes "object:<session>:<k>") and the object database's models
// (object_update_t: meshes "model:<id>", placed where the session that updated them saw them;
// a model replaces the change-event objects it was made from), their boxes in "objects"; the
// ESDF slice as "esdf"; map_stats_t with the view's own counters as "stats"; and "hello".
// No Strata process publishes planned paths on LCM, so there is no "path" item.
//
// Latency: mesh headers carry t_pub_us = mesh_update_t.utime, the mapper's wall clock when it
// made the update (microseconds since the Unix epoch); pose headers carry the time strata-view
// received the pose (pose_t.utime is the capture time, a dataset's clock when played back).
//
// Errors: a message that does not decode or holds content no viewer should show (view/
// live_decode.h, view/live_items.h) is counted, reported to the error callback, and skipped;
// the scene stays as it was before it. A gap in mesh_update_t.sequence (an update lost) is
// counted: the view cannot ask for the full mesh (it publishes nothing); a REQUEST_MESH command
// (command_t) from another process makes the mapper resend it.
//
// Threads: the handlers run on the thread that dispatches the LCM object (handle(), or another
// object's receive loop sharing it, as on memq://), one at a time; answer() (the server's thread)
// and counters() may run beside them.
#include <atomic>
#include <cstdint>
#include <functional>
#include <lcm/lcm-cpp.hpp>
#include <map>
#include <memory>
#include <mutex>
#include <nlohmann/json.hpp>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "strata/lcm/channels.h"
#include "view/scene.h"
#include "view/scene_items.h"

namespace strata::view {

/// The channels strata-view subscribes to; the defaults are those the processes publish on.
struct LiveChannels {
  std::string mesh = lcm_io::kMeshChannel;               // mesh_update_t (strata-mapper)
  std::string esdf = lcm_io::kEsdfChannel;               // esdf_slice_t (strata-mapper)
  std::string stats = lcm_io::kStatsChannel;             // map_stats_t (strata-mapper)
  std::string change = lcm_io::kChangeChannel;           // change_event_t (strata-mapper)
  std::string objects = lcm_io::kObjectsChannel;         // object_update_t (strata-mapper)
  std::string pose = lcm_io::kPoseChannel;               // pose_t T_W_C (strata-vio, strata-play)
  std::string rgbd = lcm_io::kRgbdChannel;               // rgbd_frame_t: its pose only
  std::string camera_info = lcm_io::kCameraInfoChannel;  // camera_info_t (strata-play)
};

struct LiveCounters {
  std::uint64_t messages = 0;           // received on any channel, good or bad
  std::uint64_t bad_messages = 0;       // counted and skipped
  std::uint64_t mesh_updates = 0;       // applied
  std::uint64_t mesh_updates_lost = 0;  // sequence gaps
  std::uint64_t blocks = 0;             // mesh blocks in the scene now
  std::uint64_t poses = 0;              // applied, both sources
  /// From mesh_update_t.utime (the mapper's clock) to the update being in the scene, wall ms:
  /// the last one and the largest.
  double mesh_latency_ms_last = 0.0;
  double mesh_latency_ms_max = 0.0;
  std::string last_error;
};

class LiveView {
 public:
  /// Called with a line for the first bad messages and every 100th after (the view's log).
  using ErrorLog = std::function<void(const std::string& line)>;

  /// Subscribes on `lcm` (it and `scene` must outlive the view) and puts "hello" (titled `title`).
  LiveView(lcm::LCM& lcm, Scene& scene, LiveChannels channels, const std::string& title,
           ErrorLog log = nullptr);
  ~LiveView();  // unsubscribes
  LiveView(const LiveView&) = delete;
  LiveView& operator=(const LiveView&) = delete;

  /// Dispatches the messages that arrive within `timeout_ms` on this thread (lcm::LCM's
  /// handleTimeout: > 0 one or more handled, 0 none in time, < 0 the LCM object failed), then
  /// puts the trajectories and stats when kFlushPeriod has passed since they were last put.
  int handle(int timeout_ms);
  /// Puts the trajectories and stats that changed since they were last put. Dispatch thread.
  void flush();

  /// A client request: {"type": "query", "id": n, "point": [x, y, z]} -> the distance there read
  /// from the latest ESDF slice (view/live_items.h sliceDistance) when the point lies within half
  /// a cell of the slice's height; an "error" message when there is no slice yet or the point is
  /// off it. {"type": "slice"} -> an "error" message: the mapper chooses the live slice's height.
  /// InputError for a malformed request. Thread safe.
  Message answer(const nlohmann::json& request);

  LiveCounters counters() const;  // thread safe

  /// Trajectories and stats are put at most this often (a pose stream of hundreds per second
  /// would otherwise re-send the whole polyline with each).
  static constexpr double kFlushPeriod_s = 0.1;
  /// A trajectory longer than this keeps every other point (the path's shape, bounded memory).
  static constexpr std::size_t kMaxTrajectoryPoints = 20000;
  /// Objects (change-event segments and models) beyond this are refused as bad messages.
  static constexpr std::size_t kMaxObjects = 1000;

 private:
  struct Trajectory {
    std::vector<Eigen::Vector3f> points_W;
    bool dirty = false;
  };

  void onMesh(const lcm::ReceiveBuffer* buffer, const std::string& channel);
  void onEsdf(const lcm::ReceiveBuffer* buffer, const std::string& channel);
  void onStats(const lcm::ReceiveBuffer* buffer, const std::string& channel);
  void onChange(const lcm::ReceiveBuffer* buffer, const std::string& channel);
  void onObjects(const lcm::ReceiveBuffer* buffer, const std::string& channel);
  void onPose(const lcm::ReceiveBuffer* buffer, const std::string& channel);
  void onFrame(const lcm::ReceiveBuffer* buffer, const std::string& channel);
  void onCameraInfo(const lcm::ReceiveBuffer* buffer, const std::string& channel);
  /// Runs `apply` on a received message; an exception is counted and logged, never thrown.
  template <typename Apply>
  void guarded(const std::string& channel, Apply apply);
  void applyPose(std::int64_t utime, const Eigen::Isometry3d& T_W_C, Trajectory* trajectory);
  void putObjects();
  void putStats();

  lcm::LCM& lcm_;
  Scene& scene_;
  LiveChannels channels_;
  ErrorLog log_;
  std::vector<lcm::Subscription*> subscriptions_;

  // Dispatch thread only.
  std::set<std::string> blocks_;  // block ids with a surface
  std::optional<std::int64_t> last_sequence_;
  std::optional<std::array<double, 6>> intrinsics_;
  Trajectory map_trajectory_, vio_trajectory_;
  struct ObjectItem {
    ObjectBox box;
    std::string mesh_id;
  };
  std::map<std::string, ObjectItem> objects_;  // by mesh id
  nlohmann::json mapper_stats_ = nlohmann::json::object();
  bool stats_dirty_ = false;
  double last_flush_s_ = 0.0;

  mutable std::mutex mutex_;  // guards the members below
  LiveCounters counters_;
  std::optional<EsdfSliceImage> slice_;
};

}  // namespace strata::view
