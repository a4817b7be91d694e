#pragma once
// What strata-play replays: a TUM RGB-D folder or a synthetic world session, as a Dataset.
#include <memory>
#include <string>
#include <vector>

#include "strata/io/open_dataset.h"
#include "strata/sim/sensors/imu.h"

namespace strata::apps {

struct PlaySource {
  std::unique_ptr<Dataset> dataset;
  /// Synthetic sessions only: the session's IMU samples (timestamp_ns from the session's t = 0).
  std::vector<sim::ImuSample> imu;
};

/// "sim:WORLD[:SESSION]" (SESSION default 0) or a folder for openDataset. Throws InputError
/// naming the problem (unknown world, session out of range, missing folder...).
PlaySource openPlaySource(const std::string& spec, int sim_frames, bool sim_noise, bool with_imu);

}  // namespace strata::apps
