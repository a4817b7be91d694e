#pragma once
// strata-play on an EuRoC/ASL session folder (io/euroc_dataset.h): grey stereo (or mono) frames as
// stereo_image_t and IMU samples as imu_t, merged in time order (an IMU sample before a frame of
// the same stamp), at the recording's rate times --rate, or as fast as possible with --rate 0 (no
// mapper is involved: there is no flow control). --first/--frames/--stride pick frames; the IMU
// samples sent are those from the first picked frame to the last (all when every frame is sent).
// runPlay takes this path for a folder with mav0/ and no TUM depth.txt, or for a mav0/ folder.
// EurocStream is the sending half, also used by --with-stereo (play_run.cpp), which interleaves
// a `strata sim --stereo` session's grey stereo + IMU with its RGB-D frames.
// Thread safety: not thread safe (one LCM publisher).
#include <cstddef>
#include <cstdint>
#include <lcm/lcm-cpp.hpp>
#include <string>
#include <vector>

#include "strata/io/euroc_dataset.h"
#include "player/play_options.h"

namespace strata::apps {

struct EurocPlaySummary {
  std::size_t frames = 0;
  std::size_t imu_samples = 0;
  std::size_t bytes = 0;  // encoded messages
  double seconds = 0.0;
};

/// Sends the events of an opened EuRoC session on options.stereo_channel / options.imu_channel.
class EurocStream {
 public:
  /// Opens `folder` (a session folder holding mav0/, or mav0/ itself). Throws InputError when
  /// the reader refuses it.
  EurocStream(const std::string& folder, const PlayOptions& options, lcm::LCM& lcm);

  const euroc::EurocDataset& dataset() const { return dataset_; }
  /// Publishes `event` stamped `utime` (microseconds). Throws InputError when LCM refuses it.
  void publish(const euroc::Event& event, std::int64_t utime);
  /// What was sent so far (seconds: not set here).
  const EurocPlaySummary& sent() const { return sent_; }

 private:
  euroc::EurocDataset dataset_;
  lcm::LCM& lcm_;
  std::string stereo_channel_, imu_channel_;
  std::string left_name_, right_name_;
  EurocPlaySummary sent_;
};

/// Publishes the session in `options.dataset` on options.stereo_channel and options.imu_channel.
/// Stamps: now + the recording's offsets, or with restamp = false the recording's own (ns / 1000).
/// Throws InputError for a folder the reader refuses or options that select no frame.
EurocPlaySummary playEuroc(const PlayOptions& options, lcm::LCM& lcm);

}  // namespace strata::apps
