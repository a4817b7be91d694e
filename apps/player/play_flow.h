#pragma once
// The player's view of the mapper, from its map_stats_t: how many frames it has accounted for
// (fused, dropped, rejected) and which command it handled last. Used for flow control ("as fast
// as the mapper takes it") and to wait for replies.
// Thread safety: not thread safe; pump() must be the only caller of the LCM's handle().
#include <chrono>
#include <cstdint>
#include <lcm/lcm-cpp.hpp>
#include <optional>
#include <string>

#include "strata/map_stats_t.hpp"

namespace strata::apps {

class MapperWatcher {
 public:
  MapperWatcher(lcm::LCM& lcm, const std::string& stats_channel);
  ~MapperWatcher();

  /// Handles incoming messages for up to `timeout_ms`.
  void pump(int timeout_ms);
  /// Waits until `ready()` holds or `timeout_s` passes; returns whether it holds.
  template <typename Ready>
  bool waitFor(Ready ready, double timeout_s);

  bool heard() const { return latest_.has_value(); }
  const map_stats_t& latest() const { return *latest_; }
  /// Frames the mapper has finished with (fused, dropped or rejected) since it was first heard.
  std::int64_t framesAccounted() const;
  /// Whether the mapper reported `request_id` handled; its result then in `result`.
  bool commandDone(std::int64_t request_id, std::string* result) const;

 private:
  void onStats(const lcm::ReceiveBuffer* buffer, const std::string& channel);
  static std::int64_t accounted(const map_stats_t& s);

  lcm::LCM& lcm_;
  lcm::Subscription* subscription_;
  std::optional<map_stats_t> latest_;
  std::int64_t baseline_ = 0;  // accounted frames when first heard
};

template <typename Ready>
bool MapperWatcher::waitFor(Ready ready, double timeout_s) {
  const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout_s);
  while (!ready()) {
    if (std::chrono::steady_clock::now() >= end) return false;
    pump(50);
  }
  return true;
}

}  // namespace strata::apps
