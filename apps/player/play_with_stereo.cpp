#include "player/play_with_stereo.h"

#include <filesystem>

#include "strata/core/error.h"

namespace strata::apps {

std::string mav0Folder(const PlayOptions& options) {
  const std::filesystem::path mav0 = std::filesystem::path(options.dataset) / "mav0";
  if (!std::filesystem::is_directory(mav0)) {
    throw InputError("--with-stereo: '" + options.dataset +
                     "' has no mav0/ (grey stereo + IMU; `strata sim --stereo` writes one)");
  }
  return mav0.string();
}

GreyInterleave::GreyInterleave(const PlayOptions& options, lcm::LCM& lcm)
    : stream_(mav0Folder(options), options, lcm), events_(stream_.dataset().events()) {}

bool GreyInterleave::covers(std::int64_t t_ns) const {
  const auto& frames = stream_.dataset().frames();
  return t_ns >= frames.front().timestamp_ns && t_ns <= frames.back().timestamp_ns;
}

bool GreyInterleave::pastEnd(std::int64_t t_ns) const {
  return t_ns > stream_.dataset().frames().back().timestamp_ns;
}

void GreyInterleave::skipBefore(std::int64_t t_ns) {
  while (next_ < events_.size() && events_[next_].timestamp_ns < t_ns) ++next_;
}

void GreyInterleave::sendThrough(std::int64_t t_ns, const Pace& pace) {
  last_through_ns_ = t_ns;
  for (; next_ < events_.size() && events_[next_].timestamp_ns <= t_ns; ++next_) {
    stream_.publish(events_[next_], pace(events_[next_].timestamp_ns));
  }
}

void GreyInterleave::finish(const Pace& pace) {
  if (!last_through_ns_) return;
  for (; next_ < events_.size(); ++next_) {
    const euroc::Event& e = events_[next_];
    stream_.publish(e, pace(e.timestamp_ns));
    if (e.kind == euroc::Event::Kind::kFrame && e.timestamp_ns >= *last_through_ns_) {
      ++next_;
      return;
    }
  }
}

}  // namespace strata::apps
