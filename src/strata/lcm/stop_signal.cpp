#include "strata/lcm/stop_signal.h"

#include <csignal>
#include <mutex>

namespace strata::lcm_io {
namespace {

std::atomic<bool> g_stop{false};

extern "C" void onStopSignal(int) { g_stop = true; }

}  // namespace

const std::atomic<bool>& installStopSignals() {
  static std::once_flag once;
  std::call_once(once, [] {
    struct sigaction action {};
    action.sa_handler = onStopSignal;
    sigemptyset(&action.sa_mask);
    sigaction(SIGINT, &action, nullptr);
    sigaction(SIGTERM, &action, nullptr);
  });
  return g_stop;
}

}  // namespace strata::lcm_io
