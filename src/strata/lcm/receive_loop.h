#pragma once
// The receive loop of the LCM processes: handles incoming messages until `receiving` turns false.
// When the provider stops delivering (the end of a file:// log, a socket error), `stopped` is
// called once and the loop keeps polling every `timeout_ms`, so that the process goes on with what
// it already has until it is told to stop. Thread safety: runs on the calling thread (the one that
// owns `input`); `receiving` may be cleared from any thread.
#include <atomic>
#include <chrono>
#include <functional>
#include <lcm/lcm-cpp.hpp>
#include <thread>

namespace strata::lcm_io {

inline void receiveUntilStopped(lcm::LCM& input, const std::atomic<bool>& receiving, int timeout_ms,
                                const std::function<void()>& stopped) {
  bool reported = false;
  while (receiving) {
    if (input.handleTimeout(timeout_ms) < 0) {
      if (!reported && stopped) stopped();
      reported = true;
      std::this_thread::sleep_for(std::chrono::milliseconds(timeout_ms));
    }
  }
}

}  // namespace strata::lcm_io
