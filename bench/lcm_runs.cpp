#include "lcm_runs.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <deque>
#include <lcm/lcm-cpp.hpp>
#include <mutex>
#include <thread>

#include "mapper_node/mapper_core.h"
#include "mapper_node/mapper_node.h"
#include "player/play_publisher.h"
#include "strata/core/error.h"
#include "strata/lcm/lcm_time.h"
#include "strata/map_stats_t.hpp"
#include "strata/mesh_update_t.hpp"

namespace strata::bench {
namespace {

constexpr double kAccountTimeoutS = 60.0;

/// What comes back from the mapper; handlers run on the mapper's receive thread.
struct Receiver {
  std::mutex mutex;
  std::condition_variable changed;
  std::deque<std::int64_t> unmeshed_utimes;  // published, no mesh update with them yet
  std::vector<double> latency_ms;
  double mesh_bytes = 0.0;
  std::size_t mesh_updates = 0;
  std::int64_t accounted = 0;  // frames fused + dropped + rejected (map_stats_t)
  map_stats_t stats{};
};

void onMesh(const lcm::ReceiveBuffer* buffer, const std::string&, Receiver* r) {
  const std::int64_t now = lcm_io::nowUtime();
  mesh_update_t update;
  if (update.decode(buffer->data, 0, static_cast<int>(buffer->data_size)) < 0) return;
  std::lock_guard<std::mutex> lock(r->mutex);
  r->mesh_bytes += static_cast<double>(buffer->data_size);
  ++r->mesh_updates;
  while (!r->unmeshed_utimes.empty() && r->unmeshed_utimes.front() <= update.last_frame_utime) {
    r->latency_ms.push_back(1e-3 * static_cast<double>(now - r->unmeshed_utimes.front()));
    r->unmeshed_utimes.pop_front();
  }
  r->changed.notify_all();
}

void onStats(const lcm::ReceiveBuffer* buffer, const std::string&, Receiver* r) {
  map_stats_t stats;
  if (stats.decode(buffer->data, 0, static_cast<int>(buffer->data_size)) < 0) return;
  std::lock_guard<std::mutex> lock(r->mutex);
  r->accounted = stats.frames_fused + stats.frames_dropped_backlog + stats.frames_rejected;
  r->stats = stats;
  r->changed.notify_all();
}

/// Blocks until at most `in_flight` sent frames are unaccounted for; false on timeout.
bool waitAccounted(Receiver& r, std::size_t sent, int in_flight) {
  std::unique_lock<std::mutex> lock(r.mutex);
  return r.changed.wait_for(lock, std::chrono::duration<double>(kAccountTimeoutS), [&] {
    return static_cast<std::int64_t>(sent) - r.accounted <= in_flight;
  });
}

}  // namespace

LcmRun runLcm(vk::Context& context, const std::vector<RgbdFrame>& frames,
              const CameraIntrinsics& intrinsics, const LcmRunSettings& s) {
  lcm::LCM lcm(s.url);
  if (!lcm.good()) throw InputError("LCM URL '" + s.url + "' could not be opened");
  Receiver receiver;
  lcm.subscribeFunction(s.mapper.channels.mesh, &onMesh, &receiver);
  lcm.subscribeFunction(s.mapper.channels.stats, &onStats, &receiver);
  apps::MapperCore core(context, s.mapper);
  apps::MapperNode node(lcm, lcm, core, s.mapper);
  std::atomic<bool> stop{false};
  std::thread mapper([&] { node.run(stop); });

  lcm_io::FrameEncoding encoding;
  encoding.depth = s.depth_encoding;
  apps::FramePublisher publisher(lcm, apps::PublisherChannels::defaults(), "depth", encoding);
  LcmRun run;
  run.window = s.window;
  std::int64_t last_utime = 0;
  bool complete = true;
  const auto start = std::chrono::steady_clock::now();
  for (const RgbdFrame& frame : frames) {
    if (!(complete = waitAccounted(receiver, run.frames_sent, s.window - 1))) break;
    const std::int64_t utime = std::max(lcm_io::nowUtime(), last_utime + 1);
    {
      std::lock_guard<std::mutex> lock(receiver.mutex);
      receiver.unmeshed_utimes.push_back(utime);
    }
    run.frame_bytes = static_cast<double>(publisher.publish(frame, intrinsics, utime));
    last_utime = utime;
    ++run.frames_sent;
  }
  complete = complete && waitAccounted(receiver, run.frames_sent, 0);
  run.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  stop = true;
  mapper.join();
  if (!complete) throw Error("the mapper stopped accounting for frames (see its log above)");
  std::lock_guard<std::mutex> lock(receiver.mutex);
  run.latency_ms = receiver.latency_ms;
  run.frames_meshed = receiver.latency_ms.size();
  run.frames_fused = receiver.stats.frames_fused;
  run.frames_dropped = receiver.stats.frames_dropped_backlog;
  run.fuse_ms_mean = receiver.stats.fuse_ms_mean;
  run.mesh_update_bytes =
      receiver.mesh_updates ? receiver.mesh_bytes / static_cast<double>(receiver.mesh_updates) : 0;
  return run;
}

Json lcmRunJson(const LcmRun& r) {
  std::vector<double> sorted = r.latency_ms;
  std::sort(sorted.begin(), sorted.end());
  const auto quantile = [&](double q) {
    return sorted.empty() ? 0.0 : sorted[static_cast<std::size_t>(q * (sorted.size() - 1))];
  };
  double mean = 0.0;
  for (double v : sorted) mean += v / static_cast<double>(sorted.size());
  return Json::object()
      .set("window_frames", r.window)
      .set("frames_sent", static_cast<std::int64_t>(r.frames_sent))
      .set("frames_fused", r.frames_fused)
      .set("frames_dropped", r.frames_dropped)
      .set("frames_with_mesh_update", static_cast<std::int64_t>(r.frames_meshed))
      .set("seconds", r.seconds)
      .set("frames_per_s", r.seconds > 0 ? static_cast<double>(r.frames_fused) / r.seconds : 0.0)
      .set("latency_ms", Json::object()
                             .set("mean", mean)
                             .set("p50", quantile(0.5))
                             .set("p95", quantile(0.95))
                             .set("max", sorted.empty() ? 0.0 : sorted.back()))
      .set("mapper_fuse_ms_mean", r.fuse_ms_mean)
      .set("frame_message_bytes", r.frame_bytes)
      .set("mesh_update_bytes_mean", r.mesh_update_bytes);
}

}  // namespace strata::bench
