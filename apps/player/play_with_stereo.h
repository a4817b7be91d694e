#pragma once
// strata-play --with-stereo: a `strata sim --stereo` session folder holds one trajectory twice,
// as TUM RGB-D (for the mapper) and as grey stereo + IMU in mav0/ (for a VIO such as strata-vio),
// with one time base (mav0's nanoseconds are the TUM files' seconds x 1e9). GreyInterleave sends
// the grey frames and IMU samples between the RGB-D frames in time order, so that the robot chain
// strata-play -> strata-vio -> strata-mapper runs without truth poses (with --no-poses).
// RGB-D frames outside the grey recording are not sent (no VIO pose could bracket them); after
// the last RGB-D frame the grey stream goes on through the first grey frame at or after it, so
// the VIO publishes a pose on each side of every RGB-D frame.
// Thread safety: not thread safe (one LCM publisher).
#include <cstdint>
#include <functional>
#include <lcm/lcm-cpp.hpp>
#include <optional>
#include <string>
#include <vector>

#include "player/play_euroc.h"

namespace strata::apps {

/// The mav0/ folder of options.dataset; InputError naming the dataset when it has none (checked
/// by play() before the dataset is read).
std::string mav0Folder(const PlayOptions& options);

class GreyInterleave {
 public:
  /// Called before each grey event with its recording time (ns); paces the replay and returns
  /// the utime to stamp the event with (the RGB-D frames' clock).
  using Pace = std::function<std::int64_t(std::int64_t t_ns)>;

  /// Opens the mav0/ of `options.dataset`. Throws InputError naming the folder when it has none
  /// or the reader refuses it.
  GreyInterleave(const PlayOptions& options, lcm::LCM& lcm);

  /// Whether an RGB-D frame at `t_ns` lies within the grey recording (first to last grey frame),
  /// and whether it lies after its end (so do all later frames).
  bool covers(std::int64_t t_ns) const;
  bool pastEnd(std::int64_t t_ns) const;
  /// Events before `t_ns` (the first RGB-D frame sent) will not be sent.
  void skipBefore(std::int64_t t_ns);
  /// Sends the events not yet sent up to and including `t_ns` (grey before an RGB-D frame of the
  /// same stamp).
  void sendThrough(std::int64_t t_ns, const Pace& pace);
  /// After the last RGB-D frame: sends the events not yet sent through the first grey frame at or
  /// after the last sendThrough time (nothing when no RGB-D frame was sent).
  void finish(const Pace& pace);

  const EurocPlaySummary& sent() const { return stream_.sent(); }

 private:
  EurocStream stream_;
  std::vector<euroc::Event> events_;
  std::size_t next_ = 0;
  std::optional<std::int64_t> last_through_ns_;
};

}  // namespace strata::apps
