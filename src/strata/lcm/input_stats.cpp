#include "strata/lcm/input_stats.h"

#include <cstdio>

namespace strata::lcm_io {

InputStats::InputStats(std::string log_prefix, bool log)
    : prefix_(std::move(log_prefix)), log_(log) {}

void InputStats::countBad(const std::string& channel, const std::string& reason) {
  std::int64_t count = 0;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    count = ++bad_[channel];
    ++total_;
  }
  if (!log_) return;
  if (count <= kLoggedPerChannel || count % kLogEvery == 0) {
    std::fprintf(stderr, "%s: bad message #%lld on %s: %s%s\n", prefix_.c_str(),
                 static_cast<long long>(count), channel.c_str(), reason.c_str(),
                 count == kLoggedPerChannel ? " (further ones logged every 1000th)" : "");
  }
}

std::int64_t InputStats::totalBad() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return total_;
}

std::map<std::string, std::int64_t> InputStats::badByChannel() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return bad_;
}

}  // namespace strata::lcm_io
