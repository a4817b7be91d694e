#pragma once
// Localisation of one live frame against a prior map (prior_map.h): the camera's pose in the map
// frame with its covariance, or "not localised" with the reason. The alignment pipeline's own
// steps, not a second implementation: candidates from the place index (ORB appearance), from the
// surface descriptor and, when the caller has a pose prior (the fused odometry), from the map
// keyframes near that prior; each candidate verified by align::verifyLoop (PnP RANSAC + dense ICP;
// only when no appearance candidate verifies is the frame's surface described and the prior's
// and the surface descriptor's candidates verified by FPFH RANSAC + dense ICP). The accepted verification with the most ICP
// overlap gives the pose; where several were accepted they must agree (within
// max_disagreement), else the frame is refused as ambiguous.
// Frames: W the map frame, C the live camera (x right, y down, z forward); metres, radians.
// Covariance order (tx ty tz rx ry rz) of a right-multiplied perturbation T_W_C * Exp(delta), as
// in the store.
// Errors: InputError for images whose sizes disagree with the intrinsics; unlucky data (no
// candidate, failed verification) is a result, never an exception.
// Thread safety: localize() is const and may run from several threads at once.
#include <Eigen/Geometry>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>

#include "strata/align/loop_verifier.h"
#include "strata/localize/prior_map.h"

namespace strata::localize {

struct LocalizerConfig {
  align::VerifyConfig verify;
  std::size_t appearance_candidates = 4;  // best place-index candidates verified
  int min_votes = 12;                     // place-index votes a candidate needs
  std::size_t surface_candidates = 2;     // nearest by surface descriptor, beyond those
  /// With a pose prior: the map keyframes whose camera centre lies within prior_radius_m of the
  /// prior's and whose viewing direction is within prior_max_angle_rad, nearest first, are
  /// verified too (the place index cannot tell apart places that look alike or have no texture).
  std::size_t prior_candidates = 3;
  double prior_radius_m = 1.5;
  double prior_max_angle_rad = 0.8;
  /// Accepted verifications farther apart than this (translation, rotation) make the frame
  /// ambiguous: refused.
  double max_disagreement_m = 0.25;
  double max_disagreement_rad = 0.15;
  /// Stop verifying once this many candidates were accepted and agree.
  std::size_t enough_accepted = 2;
  void validate() const;
};

/// A pose the caller believes (e.g. the fused odometry's prediction); used to propose candidates,
/// never to accept or refuse a verification (the fusion's gate does that).
struct PosePrior {
  Eigen::Isometry3d T_W_C = Eigen::Isometry3d::Identity();
};

struct Localization {
  bool localized = false;
  std::string reason;  // why not ("" when localised)
  Eigen::Isometry3d T_W_C = Eigen::Isometry3d::Identity();
  Eigen::Matrix<double, 6, 6> covariance = Eigen::Matrix<double, 6, 6>::Identity();
  std::size_t keyframe = 0;         // index into PriorMap::keyframes() of the measurement used
  std::size_t candidates = 0;       // verified
  std::size_t accepted = 0;         // of those, accepted by the verifier
  int inliers = 0;                  // PnP (or FPFH RANSAC) inliers of the measurement used
  double residual_m = 0.0;          // its ICP RMS
  double overlap = 0.0;             // its ICP overlap
  bool from_surface = false;        // measured by the surface path
  std::string candidate_source;     // "appearance", "surface" or "prior"
  double time_ms = 0.0;             // wall time of localize(), of which:
  double features_ms = 0.0;         //   ORB extraction
  double surface_ms = 0.0;          //   the surface description (only when appearance failed)
  double verify_ms = 0.0;           //   verifications
};

class Localizer {
 public:
  /// `map` must outlive the Localizer.
  explicit Localizer(const PriorMap& map, const LocalizerConfig& config = {});

  /// Localises a frame (colour for ORB; depth in metres, 0 or NaN unknown).
  Localization localize(const ColorImage& color, const DepthImage& depth,
                        const CameraIntrinsics& intrinsics,
                        const std::optional<PosePrior>& prior = std::nullopt) const;

  const PriorMap& map() const { return map_; }
  const LocalizerConfig& config() const { return config_; }

 private:
  const PriorMap& map_;
  LocalizerConfig config_;
};

}  // namespace strata::localize
