#pragma once
// The simulator's settings from a program's few options: a world with seed and session-count
// overrides, a session's rendering settings and the grey stereo + IMU recording's.
// Errors: World::load's (InputError for a missing or malformed world file).
#include <memory>
#include <string>

#include "strata/sim/session/sim_session.h"
#include "strata/sim/session/stereo_recording.h"
#include "strata/sim/world/world.h"

namespace strata::sim {

/// Loads `path` ("" = the shipped room) with optional seed / session count overrides (0 = file's).
std::shared_ptr<const World> loadWorld(const std::string& path, std::uint64_t seed,
                                            int sessions);

SimSessionConfig sessionConfig(double rate_hz, int max_frames, bool noise, bool drift);

/// The grey camera + IMU recording of `strata sim --stereo` and `strata demo --vio` at
/// width x height; without noise the images and the IMU are exact (no exposure changes, biases
/// zero).
StereoRecordingConfig stereoRecordingConfig(int width_px, int height_px, bool noise);

}  // namespace strata::sim
