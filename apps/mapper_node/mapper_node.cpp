// MapperNode, receive side: subscriptions and the handlers of the input channels.
#include "mapper_node/mapper_node.h"

#include <cstdio>
#include <exception>
#include <thread>

#include "strata/camera_info_t.hpp"
#include "strata/core/error.h"
#include "strata/lcm/convert_frame.h"
#include "strata/lcm/convert_pose.h"
#include "strata/lcm/receive_loop.h"
#include "strata/pose_t.hpp"

namespace strata::apps {
namespace {

constexpr int kReceiveTimeoutMs = 50;

/// Runs `handle`; bad input is counted on `channel` (with `on_bad` for frame accounting) and
/// logged, never thrown into LCM's dispatch.
template <typename Handle, typename OnBad>
void guarded(lcm_io::InputStats& stats, const std::string& channel, Handle handle, OnBad on_bad) {
  try {
    handle();
  } catch (const InputError& e) {
    stats.countBad(channel, e.what());
    on_bad();
  } catch (const std::exception& e) {
    stats.countBad(channel, std::string("unexpected: ") + e.what());
    on_bad();
  }
}

}  // namespace

MapperNode::MapperNode(lcm::LCM& input, lcm::LCM& output, MapperCore& core,
                       const MapperOptions& options)
    : input_(input),
      output_(output),
      core_(core),
      options_(options),
      input_stats_("strata-mapper"),
      queue_(options.queue_capacity) {
  if (!input_.good()) throw InputError("LCM input '" + options.url + "' could not be opened");
  if (!output_.good()) throw InputError("LCM output could not be opened");
  const MapperChannels& c = options_.channels;
  subscriptions_.push_back(input_.subscribe(c.rgbd, &MapperNode::onFrame, this));
  subscriptions_.push_back(input_.subscribe(c.pose, &MapperNode::onPose, this));
  subscriptions_.push_back(input_.subscribe(c.camera_info, &MapperNode::onCameraInfo, this));
  subscriptions_.push_back(input_.subscribe(c.command, &MapperNode::onCommand, this));
}

MapperNode::~MapperNode() {
  for (lcm::Subscription* s : subscriptions_) input_.unsubscribe(s);
}

void MapperNode::receiveLoop() {
  // NOTE: the input stops e.g. at the end of a log file (file:// provider): keep fusing what is
  // queued.
  lcm_io::receiveUntilStopped(input_, receiving_, kReceiveTimeoutMs, [this] {
    log("LCM input stopped delivering messages (end of log or socket error)");
  });
}

void MapperNode::onFrame(const lcm::ReceiveBuffer* buffer, const std::string& channel) {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    ++counters_.frames_received;
  }
  guarded(
      input_stats_, channel,
      [&] {
        rgbd_frame_t message;
        lcm_io::decodePayload(buffer->data, static_cast<int>(buffer->data_size), message);
        queueReady(assembler_.onFrame(lcm_io::decodeFrame(message)));
      },
      [&] {
        std::lock_guard<std::mutex> lock(mutex_);
        ++counters_.frames_rejected;
      });
}

void MapperNode::onPose(const lcm::ReceiveBuffer* buffer, const std::string& channel) {
  guarded(
      input_stats_, channel,
      [&] {
        pose_t message;
        lcm_io::decodePayload(buffer->data, static_cast<int>(buffer->data_size), message);
        if (message.parent_frame != lcm_io::kWorldFrame) {
          throw InputError("pose in frame '" + message.parent_frame + "', expected '" +
                           lcm_io::kWorldFrame + "' (T_W_C)");
        }
        queueReady(assembler_.onPose(message.utime, lcm_io::decodePose(message)));
      },
      [] {});
}

void MapperNode::onCameraInfo(const lcm::ReceiveBuffer* buffer, const std::string& channel) {
  guarded(
      input_stats_, channel,
      [&] {
        camera_info_t message;
        lcm_io::decodePayload(buffer->data, static_cast<int>(buffer->data_size), message);
        assembler_.onCameraInfo(message.camera_id, lcm_io::decodeCameraInfo(message));
      },
      [] {});
}

void MapperNode::onCommand(const lcm::ReceiveBuffer* buffer, const std::string& channel) {
  guarded(
      input_stats_, channel,
      [&] {
        command_t message;
        lcm_io::decodePayload(buffer->data, static_cast<int>(buffer->data_size), message);
        if (message.command < command_t::START_SESSION ||
            message.command > command_t::REQUEST_MESH) {
          throw InputError("unknown command " + std::to_string(message.command));
        }
        std::lock_guard<std::mutex> lock(mutex_);
        if (commands_.size() >= kMaxQueuedCommands) {
          throw InputError("more than " + std::to_string(kMaxQueuedCommands) +
                           " commands waiting; refused");
        }
        commands_.emplace_back(++arrivals_, std::move(message));
      },
      [] {});
}

void MapperNode::queueReady(lcm_io::AssemblerOutput out) {
  for (const std::string& reason : out.drop_reasons) {
    // Like bad messages: the first ones, then every 100th, so a stalled pose source cannot flood
    // the log.
    if (++no_pose_logged_ <= 10 || no_pose_logged_ % 100 == 0) log(reason);
  }
  std::size_t dropped = 0;
  for (lcm_io::ReadyFrame& frame : out.ready) {
    frame.arrival = ++arrivals_;
    dropped += queue_.push(std::move(frame));
  }
  std::lock_guard<std::mutex> lock(mutex_);
  counters_.frames_dropped_no_pose += static_cast<std::int64_t>(out.dropped_no_pose);
  counters_.frames_dropped_backlog += static_cast<std::int64_t>(dropped);
}

MapperCounters MapperNode::counters() const {
  std::lock_guard<std::mutex> lock(mutex_);
  MapperCounters counters = counters_;
  counters.messages_bad = input_stats_.totalBad();
  return counters;
}

void MapperNode::log(const std::string& line) const {
  std::fprintf(stderr, "strata-mapper: %s\n", line.c_str());
}

}  // namespace strata::apps
