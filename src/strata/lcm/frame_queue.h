#pragma once
// The queue between receiving and fusing: bounded, and when full the oldest frame goes (a mapper
// that falls behind should fuse what the robot sees now, not what it saw a while ago).
// Thread safety: thread safe (one mutex).
#include <chrono>
#include <condition_variable>
#include <cstddef>
#include <deque>
#include <mutex>
#include <optional>

namespace strata::lcm_io {

template <typename T>
class DropOldestQueue {
 public:
  explicit DropOldestQueue(std::size_t capacity) : capacity_(capacity == 0 ? 1 : capacity) {}

  /// Adds `item`; returns how many old items were dropped to make room (0 or 1).
  std::size_t push(T item) {
    std::size_t dropped = 0;
    {
      std::lock_guard<std::mutex> lock(mutex_);
      while (items_.size() >= capacity_) {
        items_.pop_front();
        ++dropped;
      }
      items_.push_back(std::move(item));
    }
    ready_.notify_one();
    return dropped;
  }

  /// The oldest item, waiting up to `timeout` for one; nullopt on timeout.
  std::optional<T> pop(std::chrono::milliseconds timeout) {
    std::unique_lock<std::mutex> lock(mutex_);
    if (!ready_.wait_for(lock, timeout, [this] { return !items_.empty(); })) return std::nullopt;
    T item = std::move(items_.front());
    items_.pop_front();
    return item;
  }

  /// Calls `read` on the oldest item under the lock; false (and no call) when empty.
  template <typename Read>
  bool peek(Read read) const {
    std::lock_guard<std::mutex> lock(mutex_);
    if (items_.empty()) return false;
    read(items_.front());
    return true;
  }

  std::size_t size() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return items_.size();
  }
  std::size_t capacity() const { return capacity_; }

 private:
  const std::size_t capacity_;
  mutable std::mutex mutex_;
  std::condition_variable ready_;
  std::deque<T> items_;
};

}  // namespace strata::lcm_io
