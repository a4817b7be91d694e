#pragma once
// Every frame of a recorded session localised against a prior map (what `strata localize` runs):
// with the session's odometry, each frame's odometry pose is fused (pose_fusion.h) and every
// `every`-th frame is localised with the fused pose as the prior; without odometry each frame is
// localised on its own (the last localised pose as the prior) and placed only where localised.
// Before the pass, a sample of frames spread over the session is localised; when none of them
// is, the map is taken not to show the session's place and InputError says so (nothing placed).
// Frames: W the map frame, O the session's odometry frame; metres, radians, seconds.
// Errors: InputError for a sample that localises nowhere, odometry poses whose count disagrees
// with the frames, odometry time going backwards or non-finite poses (naming the frame).
// Thread safety: one call at a time per Localizer use; `frames.load()` from the calling thread.
#include <Eigen/Geometry>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "strata/core/dataset.h"
#include "strata/localize/localizer.h"
#include "strata/localize/pose_fusion.h"

namespace strata::localize {

struct SessionLocalizationConfig {
  LocalizerConfig localizer;
  FusionConfig fusion;
  int every = 1;             // localise every n-th frame (the others: odometry only)
  int check_frames = 12;     // frames of the up-front sample (0: no check)
  void validate() const;
};

struct FrameLocalization {
  std::size_t frame = 0;
  double timestamp_s = 0.0;
  bool attempted = false;     // localisation was tried at this frame
  Localization localization;  // when attempted
  FusedPose fused;            // with odometry; without: status kCorrected where localised
  bool placed() const { return fused.status != FusionStatus::kUninitialised; }
};

struct SessionLocalization {
  std::vector<FrameLocalization> frames;
  std::size_t attempted = 0, localized = 0, accepted = 0, rejected = 0;
  std::size_t check_localized = 0, check_frames = 0;  // the up-front sample
  bool with_odometry = false;
};

/// done of total frames; return false to stop (the result then holds the frames done).
using SessionProgress = std::function<bool(std::size_t done, std::size_t total)>;

/// `odometry_T_O_C`: per frame of `frames`, or empty (no odometry).
SessionLocalization localizeSession(const Dataset& frames,
                                    const std::vector<Eigen::Isometry3d>& odometry_T_O_C,
                                    const PriorMap& map, const SessionLocalizationConfig& config,
                                    const SessionProgress& progress = {});

}  // namespace strata::localize
