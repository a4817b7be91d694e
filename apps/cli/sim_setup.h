#pragma once
// Shared by `strata sim` and `strata demo`: the world, session and recording settings from the
// options.
#include <memory>
#include <string>

#include "sim/session/sim_session.h"
#include "sim/session/stereo_recording.h"
#include "sim/world/world.h"

namespace strata::apps {

/// Loads `path` ("" = the shipped room) with optional seed / session count overrides (0 = file's).
std::shared_ptr<const sim::World> loadWorld(const std::string& path, std::uint64_t seed,
                                            int sessions);

sim::SimSessionConfig sessionConfig(double rate_hz, int max_frames, bool noise, bool drift);

/// The grey camera + IMU recording of `strata sim --stereo` and `strata demo --vio` at
/// width x height; without noise the images and the IMU are exact (no exposure changes, biases
/// zero).
sim::StereoRecordingConfig stereoRecordingConfig(int width_px, int height_px, bool noise);

}  // namespace strata::apps
