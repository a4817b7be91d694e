#include "player/play_euroc.h"

#include <chrono>
#include <thread>

#include "strata/core/progress.h"
#include "strata/core/error.h"
#include "strata/lcm/convert_stereo.h"
#include "strata/lcm/lcm_time.h"
#include "player/internal/publish.h"

namespace strata::apps {
namespace {

using Clock = std::chrono::steady_clock;

using internal::publishOrThrow;

/// Events to send: the picked frames and the IMU samples within their span (all when all frames).
std::vector<euroc::Event> pickEvents(const euroc::EurocDataset& d, const PlayOptions& o) {
  std::vector<bool> picked(d.frames().size(), false);
  std::size_t count = 0, first_index = 0, last_index = 0;
  for (std::size_t i = static_cast<std::size_t>(o.first); i < d.frames().size(); i += o.stride) {
    if (o.frames > 0 && count >= static_cast<std::size_t>(o.frames)) break;
    if (count++ == 0) first_index = i;
    last_index = i;
    picked[i] = true;
  }
  if (count == 0) throw InputError("'" + o.dataset + "' has no frames to send");
  const bool all = count == d.frames().size();
  const std::int64_t t_first = d.frames()[first_index].timestamp_ns;
  const std::int64_t t_last = d.frames()[last_index].timestamp_ns;
  std::vector<euroc::Event> events;
  for (const euroc::Event& e : d.events()) {
    if (e.kind == euroc::Event::Kind::kFrame
            ? picked[e.index]
            : all || (e.timestamp_ns >= t_first && e.timestamp_ns <= t_last)) {
      events.push_back(e);
    }
  }
  return events;
}

}  // namespace

EurocStream::EurocStream(const std::string& folder, const PlayOptions& o, lcm::LCM& lcm)
    : dataset_(euroc::EurocDataset::open(folder)),
      lcm_(lcm),
      stereo_channel_(o.stereo_channel),
      imu_channel_(o.imu_channel),
      left_name_(dataset_.calibration().cameras[0].name),
      right_name_(dataset_.stereo() ? dataset_.calibration().cameras[1].name : "") {}

void EurocStream::publish(const euroc::Event& e, std::int64_t utime) {
  if (e.kind == euroc::Event::Kind::kImu) {
    const euroc::ImuSample& s = dataset_.imu()[e.index];
    sent_.bytes += publishOrThrow(lcm_, imu_channel_,
                                  lcm_io::encodeImu({utime, "imu0", s.gyro_rad_s, s.accel_mps2}));
    ++sent_.imu_samples;
    return;
  }
  const euroc::StereoImages images = dataset_.loadImages(e.index);
  sent_.bytes += publishOrThrow(
      lcm_, stereo_channel_,
      lcm_io::encodeStereo(images.left, images.right, utime,
                           static_cast<std::int64_t>(sent_.frames), left_name_, right_name_));
  ++sent_.frames;
}

EurocPlaySummary playEuroc(const PlayOptions& o, lcm::LCM& lcm) {
  EurocStream stream(o.dataset, o, lcm);
  const std::vector<euroc::Event> events = pickEvents(stream.dataset(), o);
  std::size_t frame_events = 0;
  for (const euroc::Event& e : events) frame_events += e.kind == euroc::Event::Kind::kFrame;
  ProgressBar progress("sending", frame_events, !o.quiet);
  const auto start = Clock::now();
  const std::int64_t t0_ns = events.front().timestamp_ns;
  const std::int64_t base_utime = lcm_io::nowUtime();
  for (const euroc::Event& e : events) {
    const std::int64_t offset_ns = e.timestamp_ns - t0_ns;
    if (o.rate > 0.0) {
      std::this_thread::sleep_until(start +
                                    std::chrono::duration_cast<Clock::duration>(
                                        std::chrono::duration<double>(offset_ns * 1e-9 / o.rate)));
    }
    stream.publish(e, o.restamp ? base_utime + offset_ns / 1000 : e.timestamp_ns / 1000);
    if (e.kind == euroc::Event::Kind::kFrame) progress.update(stream.sent().frames);
  }
  progress.finish();
  EurocPlaySummary summary = stream.sent();
  summary.seconds = std::chrono::duration<double>(Clock::now() - start).count();
  return summary;
}

}  // namespace strata::apps
