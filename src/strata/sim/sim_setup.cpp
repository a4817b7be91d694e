#include "strata/sim/sim_setup.h"

#include "strata/sim/world/world_paths.h"

namespace strata::sim {

std::shared_ptr<const World> loadWorld(const std::string& path, std::uint64_t seed,
                                            int sessions) {
  World::Options options;
  if (seed != 0) options.seed = seed;
  if (sessions > 0) options.session_count = sessions;
  return std::make_shared<const World>(
      World::load(path.empty() ? sim::defaultWorldPath() : path, options));
}

SimSessionConfig sessionConfig(double rate_hz, int max_frames, bool noise, bool drift) {
  SimSessionConfig config;
  config.frame_rate_hz = rate_hz;
  config.max_frames = max_frames;
  config.drift = drift;
  config.camera.noise.enabled = noise;  // quantisation to the 16-bit format stays on
  return config;
}

StereoRecordingConfig stereoRecordingConfig(int width_px, int height_px, bool noise) {
  StereoRecordingConfig config;
  config.width_px = width_px;
  config.height_px = height_px;
  if (!noise) {
    config.pixel_noise_sigma = 0.0;
    config.exposure_gain_sigma = 0.0;
    config.exposure_offset_sigma = 0.0;
    config.imu.noise = false;
  }
  return config;
}

}  // namespace strata::sim
