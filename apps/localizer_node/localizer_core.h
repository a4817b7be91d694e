#pragma once
// strata-localizer's work without LCM: odometry poses (T_O_C, frame O of the odometry) through
// the fusion (localize/pose_fusion.h) into map-frame poses T_W_C, frames localised against the
// prior map (localize/localizer.h), and each localisation applied to the correction T_W_O.
// A frame's localisation finishes after later odometry poses came in (it takes ~100 ms): its
// measurement is carried to the latest odometry pose through the odometry between them
// (carryLocalization) before the fusion corrects with it, so a late localisation corrects the
// present pose, not the one of its frame.
// Thread safety: thread safe. odometry(), priorFor() and correct() serialise on one mutex;
// localize() runs without it (the Localizer is const), so a slow localisation never holds up the
// odometry.
#include <Eigen/Geometry>
#include <cstdint>
#include <mutex>
#include <optional>

#include "localizer_node/localizer_options.h"
#include "strata/lcm/frame_assembler.h"
#include "strata/localize/localizer.h"
#include "strata/localize/pose_fusion.h"
#include "strata/localize/prior_map.h"

namespace strata::apps {

/// `l`, measured at a frame whose odometry pose was T_O_C_frame, as a measurement at the
/// odometry pose T_O_C_now: T_W_C * T_O_C_frame^-1 * T_O_C_now, its covariance (a right
/// perturbation in camera axes) moved along by the adjoint.
localize::Localization carryLocalization(const localize::Localization& l,
                                         const Eigen::Isometry3d& T_O_C_frame,
                                         const Eigen::Isometry3d& T_O_C_now);

/// The prior map of the database options.db_path, opened read-only (nothing is written), with
/// options.map; a line on stderr unless options.quiet. InputError naming the file for one that is
/// missing, not a map, corrupt, of a newer schema, without a usable keyframe, or whose sessions'
/// folders are gone or changed.
localize::PriorMap loadPriorMap(const LocalizerOptions& options);

class LocalizerCore {
 public:
  /// `map` must outlive the core. Throws InputError for invalid options.
  LocalizerCore(const localize::PriorMap& map, const LocalizerOptions& options);

  /// An odometry pose at `utime` (microseconds). Throws InputError, changing nothing, for a stamp
  /// not after the previous pose's (time going backwards or repeating) or a non-finite pose.
  /// Returns the map-frame pose (status kUninitialised: none yet); `gap_s` (optional) gets the
  /// time since the previous pose (0 for the first).
  localize::FusedPose odometry(std::int64_t utime, const Eigen::Isometry3d& T_O_C,
                               double* gap_s = nullptr);
  /// The pose prior of a frame whose odometry pose is T_O_C (nullopt before initialisation).
  std::optional<localize::PosePrior> priorFor(const Eigen::Isometry3d& T_O_C) const;
  /// Localises a ready frame (its T_W_C is its odometry pose T_O_C; colour and depth as given).
  /// InputError for images whose sizes disagree with the intrinsics.
  localize::Localization localize(const lcm_io::ReadyFrame& frame,
                                  const std::optional<localize::PosePrior>& prior) const;
  /// Applies a localisation of the frame whose odometry pose was T_O_C_frame, carried to the
  /// latest odometry pose. Returns the fused pose at that latest pose.
  localize::FusedPose correct(const localize::Localization& l,
                              const Eigen::Isometry3d& T_O_C_frame);

  bool initialised() const;
  /// Localisations the fusion accepted (initialisation included) and rejected.
  std::size_t accepted() const;
  std::size_t rejected() const;
  const localize::PriorMap& map() const { return map_; }

 private:
  const localize::PriorMap& map_;
  const localize::Localizer localizer_;
  mutable std::mutex mutex_;  // guards the members below
  localize::PoseFusion fusion_;
  bool have_odometry_ = false;
  std::int64_t last_utime_ = 0;
  Eigen::Isometry3d last_T_O_C_ = Eigen::Isometry3d::Identity();
};

}  // namespace strata::apps
