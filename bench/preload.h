#pragma once
// Frames decoded into memory before any timing starts: decoding PNG/JPEG is not fusion time.
#include <string>
#include <vector>

#include "strata/core/types.h"

namespace strata::bench {

struct PreloadedFrames {
  std::string dataset_name;
  CameraIntrinsics intrinsics;
  std::vector<RgbdFrame> frames;  // depth in metres, colour, T_W_C
  double load_s = 0.0;            // decode time, for the record only
  double host_rss_mib = 0.0;      // current RSS once the frames are in memory
};

/// The first `max_frames` frames (0: all) of the dataset in `path`, with colour. Progress to
/// stderr. Throws InputError when the folder cannot be read or has fewer frames than asked for.
PreloadedFrames preloadFrames(const std::string& path, int max_frames);

}  // namespace strata::bench
