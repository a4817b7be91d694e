#pragma once
// strata-play on an EuRoC/ASL session folder (io/euroc_dataset.h): grey stereo (or mono) frames as
// stereo_image_t and IMU samples as imu_t, merged in time order (an IMU sample before a frame of
// the same stamp), at the recording's rate times --rate, or as fast as possible with --rate 0 (no
// mapper is involved: there is no flow control). --first/--frames/--stride pick frames; the IMU
// samples sent are those from the first picked frame to the last (all when every frame is sent).
// runPlay takes this path for a folder with mav0/ and no TUM depth.txt, or for a mav0/ folder.
// Thread safety: not thread safe (one LCM publisher).
#include <cstddef>
#include <lcm/lcm-cpp.hpp>
#include <string>

#include "player/play_options.h"

namespace strata::apps {

struct EurocPlaySummary {
  std::size_t frames = 0;
  std::size_t imu_samples = 0;
  std::size_t bytes = 0;  // encoded messages
  double seconds = 0.0;
};

/// Publishes the session in `options.dataset` on options.stereo_channel and options.imu_channel.
/// Stamps: now + the recording's offsets, or with restamp = false the recording's own (ns / 1000).
/// Throws InputError for a folder the reader refuses or options that select no frame.
EurocPlaySummary playEuroc(const PlayOptions& options, lcm::LCM& lcm);

}  // namespace strata::apps
