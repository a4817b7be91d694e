#pragma once
// The interface every source of posed RGB-D frames implements: datasets read from disk (io/),
// simulated sessions rendered on demand (sim/), frames a program holds in memory.
#include <cstddef>
#include <string>

#include "strata/core/types.h"

namespace strata {

/// When a frame was taken and where its camera was, without its images.
struct FrameStamp {
  double timestamp_s = 0.0;
  Eigen::Isometry3d T_W_C = Eigen::Isometry3d::Identity();
};

/// A finite, indexable sequence of RGB-D frames with camera-to-world poses.
/// Thread safety: load() is const and may be called from several threads at once.
class Dataset {
 public:
  virtual ~Dataset();
  /// For messages: the format and folder, e.g. "TUM RGB-D '/data/redkitchen'".
  virtual std::string name() const = 0;
  virtual std::size_t size() const = 0;
  virtual CameraIntrinsics intrinsics() const = 0;
  /// Frame `index` in [0, size()), validated (validateFrame). Depth in metres, 0 = invalid; colour
  /// may be empty. Throws InputError naming the file and the problem.
  virtual RgbdFrame load(std::size_t index) const = 0;
  /// Frame `index`'s timestamp and pose, as load() would give them, without reading or rendering
  /// its images where the source can (the default loads the frame). Throws like load().
  virtual FrameStamp stamp(std::size_t index) const;
  /// What was tolerated while opening (dropped frames, frames without colour), one line each;
  /// "" when nothing was.
  virtual std::string warnings() const { return {}; }
};

}  // namespace strata
