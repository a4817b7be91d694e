#pragma once
// The queue between strata-vio's receive thread and its VIO worker: stereo frames and IMU samples
// in arrival order (the order the pipeline expects them in). Bounded in frames: when the worker
// falls behind, the oldest waiting frame goes (the VIO bridges a missing frame on the IMU), while
// IMU samples stay (a missing sample would bend the preintegration); only beyond `max_imu` does
// the oldest sample go.
// Thread safety: thread safe (one mutex).
#include <algorithm>
#include <chrono>
#include <condition_variable>
#include <cstddef>
#include <deque>
#include <mutex>
#include <optional>
#include <variant>

#include "strata/lcm/convert_stereo.h"

namespace strata::apps {

class SensorQueue {
 public:
  using Item = std::variant<lcm_io::StereoFrameMsg, lcm_io::ImuMsg>;
  struct Dropped {
    std::size_t frames = 0;
    std::size_t imu = 0;
  };

  SensorQueue(std::size_t max_frames, std::size_t max_imu)
      : max_frames_(std::max<std::size_t>(max_frames, 1)),
        max_imu_(std::max<std::size_t>(max_imu, 1)) {}

  /// Adds `item`; returns what was dropped to make room.
  Dropped push(Item item) {
    Dropped dropped;
    {
      std::lock_guard<std::mutex> lock(mutex_);
      const bool frame = std::holds_alternative<lcm_io::StereoFrameMsg>(item);
      std::size_t& count = frame ? frames_ : imu_;
      if (count >= (frame ? max_frames_ : max_imu_)) {
        dropOldest(frame);
        ++(frame ? dropped.frames : dropped.imu);
      }
      items_.push_back(std::move(item));
      ++count;
    }
    ready_.notify_one();
    return dropped;
  }

  /// The oldest item, waiting up to `timeout` for one; nullopt on timeout.
  std::optional<Item> pop(std::chrono::milliseconds timeout) {
    std::unique_lock<std::mutex> lock(mutex_);
    if (!ready_.wait_for(lock, timeout, [this] { return !items_.empty(); })) return std::nullopt;
    Item item = std::move(items_.front());
    items_.pop_front();
    --(std::holds_alternative<lcm_io::StereoFrameMsg>(item) ? frames_ : imu_);
    return item;
  }

  bool empty() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return items_.empty();
  }

 private:
  void dropOldest(bool frame) {
    const auto oldest = std::find_if(items_.begin(), items_.end(), [frame](const Item& i) {
      return std::holds_alternative<lcm_io::StereoFrameMsg>(i) == frame;
    });
    items_.erase(oldest);
    --(frame ? frames_ : imu_);
  }

  const std::size_t max_frames_;
  const std::size_t max_imu_;
  mutable std::mutex mutex_;
  std::condition_variable ready_;
  std::deque<Item> items_;
  std::size_t frames_ = 0;
  std::size_t imu_ = 0;
};

}  // namespace strata::apps
