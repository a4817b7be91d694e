#include "player/play_flow.h"

#include <chrono>
#include <cstdio>

namespace strata::apps {

MapperWatcher::MapperWatcher(lcm::LCM& lcm, const std::string& stats_channel)
    : lcm_(lcm), subscription_(lcm.subscribe(stats_channel, &MapperWatcher::onStats, this)) {}

MapperWatcher::~MapperWatcher() { lcm_.unsubscribe(subscription_); }

void MapperWatcher::pump(int timeout_ms) {
  // Drain what is there, then wait once.
  while (lcm_.handleTimeout(0) > 0) {
  }
  lcm_.handleTimeout(timeout_ms);
}

void MapperWatcher::onStats(const lcm::ReceiveBuffer* buffer, const std::string& channel) {
  map_stats_t stats;
  if (stats.decode(buffer->data, 0, static_cast<int>(buffer->data_size)) < 0) {
    std::fprintf(stderr, "strata-play: undecodable map_stats_t on %s ignored\n", channel.c_str());
    return;
  }
  if (!latest_) baseline_ = accounted(stats);
  latest_ = std::move(stats);
}

std::int64_t MapperWatcher::accounted(const map_stats_t& s) {
  return s.frames_fused + s.frames_dropped_backlog + s.frames_dropped_no_pose + s.frames_rejected;
}

std::int64_t MapperWatcher::framesAccounted() const {
  return latest_ ? accounted(*latest_) - baseline_ : 0;
}

bool MapperWatcher::commandDone(std::int64_t request_id, std::string* result) const {
  if (!latest_ || latest_->last_command_id != request_id) return false;
  if (result != nullptr) *result = latest_->last_command_result;
  return true;
}

}  // namespace strata::apps
