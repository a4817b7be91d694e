// MapperNode, worker side: fusing, commands, publishing, the orderly stop.
#include <chrono>
#include <cstdio>
#include <thread>

#include "strata/core/error.h"
#include "strata/lcm/lcm_time.h"
#include "mapper_node/mapper_node.h"
#include "strata/objects/object_database.h"

namespace strata::apps {
namespace {

constexpr std::chrono::milliseconds kQueueWait(20);

double nowSeconds() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

/// Next due time after `now` for a rate; rate <= 0 means "every time".
double nextDue(double now_s, double rate_hz) {
  return rate_hz > 0.0 ? now_s + 1.0 / rate_hz : now_s;
}

}  // namespace

bool MapperNode::run(const std::atomic<bool>& stop) {
  receiving_ = true;
  std::thread receiver([this] { receiveLoop(); });
  const double now_s = nowSeconds();
  next_stats_s_ = now_s;
  next_mesh_s_ = nextDue(now_s, options_.mesh_rate_hz);
  next_esdf_s_ = nextDue(now_s, options_.esdf_rate_hz);
  try {
    while (!stop) workOnce();
  } catch (...) {
    receiving_ = false;  // never leave the receive thread running behind an exception
    receiver.join();
    throw;
  }
  receiving_ = false;
  receiver.join();
  // Nothing already received is lost: fuse the backlog and honour queued commands (a session's
  // end, a save) in the order they arrived, then publish and save what the map holds.
  for (;;) {
    runCommands();  // those that arrived before the oldest queued frame
    auto frame = queue_.pop(std::chrono::milliseconds(0));
    if (!frame) break;
    fuseOne(*frame);
  }
  runCommands(true);
  try {
    publishMesh(false);
    publishStats();
    publishObjectUpdates(true);
  } catch (const std::exception& e) {
    log(std::string("could not publish the last update: ") + e.what());  // the save matters more
  }
  return saveOnExit();
}

void MapperNode::workOnce() {
  runCommands();
  if (core_.objectUpdatesReady()) publishObjectUpdates();
  bool fused = false;
  if (auto frame = queue_.pop(kQueueWait)) {
    fuseOne(*frame);
    fused = true;
  }
  try {
    publishDue(fused);
  } catch (const std::exception& e) {
    // NOTE: outputs are derived from the map, which stays intact: report and keep mapping.
    log(std::string("could not publish an update: ") + e.what());
  }
}

void MapperNode::fuseOne(const lcm_io::ReadyFrame& frame) {
  try {
    keyframe_score_t score;
    if (core_.fuse(frame, &score)) output_.publish(options_.channels.keyframe, &score);
  } catch (const std::exception& e) {
    // InputError: checked before the device changed; DeviceError: the map is as before.
    log("frame at utime " + std::to_string(frame.utime) + " not fused: " + e.what());
    std::lock_guard<std::mutex> lock(mutex_);
    ++counters_.frames_rejected;
  }
}

void MapperNode::publishDue(bool frame_fused) {
  const double now_s = nowSeconds();
  if (frame_fused && (options_.mesh_rate_hz <= 0.0 || now_s >= next_mesh_s_)) {
    publishMesh(false);
    next_mesh_s_ = nextDue(now_s, options_.mesh_rate_hz);
  } else if (options_.mesh_rate_hz > 0.0 && now_s >= next_mesh_s_) {
    publishMesh(false);  // frames fused since the last update, if any
    next_mesh_s_ = nextDue(now_s, options_.mesh_rate_hz);
  }
  if (options_.esdf_rate_hz > 0.0 && now_s >= next_esdf_s_) {
    publishEsdf();
    next_esdf_s_ = nextDue(now_s, options_.esdf_rate_hz);
  }
  // Stats after every frame: the player's flow control and lcm-spy both watch them.
  if (frame_fused || now_s >= next_stats_s_) {
    publishStats();
    next_stats_s_ = nextDue(now_s, options_.stats_rate_hz);
  }
  saveDue(now_s);
}

void MapperNode::saveDue(double now_s) {
  if (options_.save_every_s <= 0.0 || options_.map_path.empty()) return;
  if (next_save_s_ == 0.0) next_save_s_ = now_s + options_.save_every_s;  // the first interval
  if (now_s < next_save_s_ || core_.framesFused() == frames_at_last_save_) return;
  next_save_s_ = now_s + options_.save_every_s;
  try {
    core_.saveMap(options_.map_path);
    frames_at_last_save_ = core_.framesFused();
    if (!options_.quiet) {
      log("saved the map (" + std::to_string(frames_at_last_save_) + " frames, every " +
          std::to_string(options_.save_every_s) + " s) to " + options_.map_path);
    }
  } catch (const std::exception& e) {
    // NOTE: the map in memory is intact and the previous file too (saves are atomic): keep
    // mapping and try again at the next interval.
    log("could not save the map to " + options_.map_path + ": " + e.what());
  }
}

void MapperNode::runCommands(bool all) {
  for (;;) {
    command_t command;
    {
      std::lock_guard<std::mutex> lock(mutex_);
      if (commands_.empty()) return;
      std::uint64_t oldest_frame = 0;
      queue_.peek([&](const lcm_io::ReadyFrame& f) { oldest_frame = f.arrival; });
      // NOTE: a frame received before the command is still queued: fuse it first.
      if (!all && oldest_frame != 0 && oldest_frame < commands_.front().first) return;
      command = std::move(commands_.front().second);
      commands_.pop_front();
    }
    std::string result;
    try {
      runCommand(command);
      result = "ok";
    } catch (const std::exception& e) {
      result = std::string("error: ") + e.what();
      log("command " + std::to_string(command.command) + " (request " +
          std::to_string(command.request_id) + ") failed: " + e.what());
    }
    {
      std::lock_guard<std::mutex> lock(mutex_);
      last_command_id_ = command.request_id;
      last_command_result_ = result;
    }
    publishStats();
  }
}

void MapperNode::runCommand(const command_t& command) {
  const std::int64_t now = lcm_io::nowUtime();
  switch (command.command) {
    case command_t::START_SESSION:
      publishChangeEvents(core_.startSession(now));  // the database updates in the background
      break;
    case command_t::STOP_SESSION:
      publishMesh(false);
      publishChangeEvents(core_.stopSession(now));
      break;
    case command_t::SAVE_MAP: {
      const std::string path = command.argument.empty() ? options_.map_path : command.argument;
      core_.saveMap(path);
      if (!options_.quiet)
        log("saved the map (" + std::to_string(core_.framesFused()) + " frames) to " + path);
      break;
    }
    case command_t::REQUEST_MESH:
      publishMesh(true);
      break;
    default:
      throw InputError("unknown command " + std::to_string(command.command));
  }
}

void MapperNode::publishMesh(bool full) {
  mesh_update_t update;
  if (core_.meshUpdate(full, lcm_io::nowUtime(), &update)) {
    output_.publish(options_.channels.mesh, &update);
  }
}

void MapperNode::publishEsdf() {
  esdf_slice_t slice;
  if (core_.esdfSlice(lcm_io::nowUtime(), &slice)) output_.publish(options_.channels.esdf, &slice);
}

void MapperNode::publishChangeEvents(const std::vector<change_event_t>& events) {
  for (const change_event_t& event : events) output_.publish(options_.channels.change, &event);
  if (!options_.quiet) {
    log("session ended: " + std::to_string(events.size()) + " changed objects published");
  }
}

void MapperNode::publishObjectUpdates(bool wait) {
  std::vector<object_update_t> updates;
  try {
    updates = core_.takeObjectUpdates(wait);
  } catch (const std::exception& e) {
    log(std::string("object database: a session could not be added (the database is as before "
                    "it): ") +
        e.what());
    return;
  }
  for (const object_update_t& update : updates) output_.publish(options_.channels.objects, &update);
  const objects::ObjectDatabase* database = core_.objectDatabase();
  if (database == nullptr) return;
  if (!options_.quiet) {
    log("object database: " + std::to_string(updates.size()) + " models created or extended, " +
        std::to_string(database->models().size()) + " in all");
  }
  // A failed write leaves the previous file and the database in memory: the next session end
  // (or the exit) tries again.
  try {
    if (core_.saveObjects() && !options_.quiet)
      log("saved the object database to " + options_.objectsFile());
  } catch (const std::exception& e) {
    log("could not save the object database to " + options_.objectsFile() + ": " + e.what());
  }
}

void MapperNode::publishStats() {
  const map_stats_t message = stats(lcm_io::nowUtime());
  output_.publish(options_.channels.stats, &message);
}

map_stats_t MapperNode::stats(std::int64_t utime) const {
  const MapperCounters c = counters();
  map_stats_t s{};
  s.utime = utime;
  s.frames_received = c.frames_received;
  s.frames_fused = core_.framesFused();
  s.frames_dropped_backlog = c.frames_dropped_backlog;
  s.frames_dropped_no_pose = c.frames_dropped_no_pose;
  s.frames_rejected = c.frames_rejected;
  s.messages_bad = c.messages_bad;
  s.queue_depth = static_cast<std::int32_t>(queue_.size());
  s.queue_capacity = static_cast<std::int32_t>(queue_.capacity());
  s.blocks = core_.blocks();
  s.device_bytes = static_cast<std::int64_t>(core_.deviceBytes());
  s.fuse_ms_last = static_cast<float>(core_.lastFuseMs());
  s.fuse_ms_mean = static_cast<float>(core_.meanFuseMs());
  s.last_frame_utime = core_.lastFrameUtime();
  s.session = core_.session();
  s.session_active = core_.sessionActive();
  {
    std::lock_guard<std::mutex> lock(mutex_);
    s.last_command_id = last_command_id_;
    s.last_command_result = last_command_result_;
  }
  for (const auto& [channel, count] : input_stats_.badByChannel()) {
    s.bad_channel.push_back(channel);
    s.bad_count.push_back(count);
  }
  s.num_channels = static_cast<std::int32_t>(s.bad_channel.size());
  return s;
}

bool MapperNode::saveOnExit() {
  bool saved = true;
  try {
    if (core_.saveObjects()) log("saved the object database to " + options_.objectsFile());
  } catch (const std::exception& e) {
    log("could not save the object database to " + options_.objectsFile() + ": " + e.what());
    saved = false;
  }
  if (options_.map_path.empty()) return saved;
  try {
    core_.saveMap(options_.map_path);
    log("saved the map (" + std::to_string(core_.framesFused()) + " frames fused) to " +
        options_.map_path);
    return saved;
  } catch (const std::exception& e) {
    log("could not save the map to " + options_.map_path + ": " + e.what());
    return false;
  }
}

}  // namespace strata::apps
