#include "strata/track/rgbd_tracker.h"

#include <Eigen/Eigenvalues>
#include <chrono>
#include <cmath>
#include <limits>
#include <sstream>

#include "strata/core/clock.h"
#include "strata/track/depth_filter.h"
#include "strata/track/gauss_newton.h"
#include "strata/track/live_pyramid.h"
#include "strata/track/photometric.h"

namespace strata {
namespace {

std::vector<LiveView> liveViews(const std::vector<LiveLevel>& pyramid) {
  std::vector<LiveView> views;
  for (const LiveLevel& level : pyramid) {
    views.push_back(LiveView{level.intrinsics.width_px, level.intrinsics.height_px, &level.vertex_C,
                             &level.normal_C});
  }
  return views;
}

std::uint32_t countHits(const vk::Buffer& normals, std::size_t pixels) {
  const auto* n = static_cast<const float*>(normals.mapped());
  std::uint32_t hits = 0;
  for (std::size_t i = 0; i < pixels; ++i) hits += n[i * 4 + 3] > 0.5f ? 1u : 0u;
  return hits;
}

TrackResult lostEarly(const Eigen::Isometry3d& T_W_C_guess, const std::string& reason) {
  TrackResult result;
  result.T_W_C = T_W_C_guess;
  result.reason = reason;
  return result;
}

/// The largest eigenvalue of a symmetric 3x3 block (infinite when any entry is not finite).
double largestEigenvalue(const Eigen::Matrix3d& m) {
  if (!m.allFinite()) return std::numeric_limits<double>::infinity();
  return Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(m).eigenvalues()[2];
}

}  // namespace

RgbdTracker::RgbdTracker(vk::Context& context, const TrackConfig& config)
    : config_(config), raycast_(context), equations_(context) {
  config_.validate();
}

AssociationGates RgbdTracker::gatesFor() const {
  AssociationGates gates;
  gates.max_distance_m = config_.max_distance_m;
  gates.min_normal_cos = static_cast<float>(std::cos(config_.max_normal_angle_deg * M_PI / 180.0));
  gates.huber_m = config_.huber_m;
  return gates;
}

TrackResult RgbdTracker::track(DeviceTsdfMap& map, int tsdf_layer, const RgbdFrame& frame,
                               const CameraIntrinsics& intrinsics,
                               const Eigen::Isometry3d& T_W_C_guess) {
  const auto start = std::chrono::steady_clock::now();
  validateFrame(frame, intrinsics);
  validatePose(T_W_C_guess, "tracking guess");
  const auto finish = [&](TrackResult result) {
    result.wall_ms = msSince(start);
    return result;
  };

  const DepthImage smoothed = bilateralFilterDepth(
      frame.depth, map.config(), config_.smoothing_sigma_px, config_.smoothing_depth_share);
  const std::vector<LiveLevel> pyramid = buildLivePyramid(
      smoothed, intrinsics, map.config(), config_.levels, config_.pyramid_depth_threshold_m);
  if (pyramid[0].valid < config_.min_inliers) {
    return finish(lostEarly(T_W_C_guess, "too little valid depth"));
  }
  RaycastOptions raycast_options;
  raycast_options.tsdf_layer = tsdf_layer;
  const CameraIntrinsics& model_intrinsics =
      pyramid[static_cast<std::size_t>(config_.model_level)].intrinsics;
  const double color_weight = config_.color_weight;
  const bool photometric = color_weight > 0.0 && !frame.color.empty();
  double raycast_ms = 0.0;
  IntensityModel model_intensity;
  std::vector<IntensityImage> live_intensity;
  if (photometric) {
    const RaycastImage model =
        raycast_.run(map, model_intrinsics, T_W_C_guess, raycast_options, &raycast_ms);
    model_intensity = intensityModel(model, model_intrinsics, T_W_C_guess);
    live_intensity.push_back(intensityOf(frame.color));
    for (int l = 1; l < config_.levels; ++l) {
      live_intensity.push_back(halfIntensity(live_intensity.back()));
    }
  } else {
    raycast_ms = raycast_.render(map, model_intrinsics, T_W_C_guess, raycast_options);
  }
  PhotometricGates photo_gates;
  photo_gates.max_distance_m = config_.max_distance_m;
  const std::size_t pixels =
      static_cast<std::size_t>(model_intrinsics.width_px) * model_intrinsics.height_px;
  if (countHits(raycast_.normalBuffer(), pixels) < config_.min_inliers) {
    TrackResult result = lostEarly(T_W_C_guess, "the map shows too little from the guess");
    result.raycast_ms = raycast_ms;
    return finish(result);
  }
  equations_.setLive(liveViews(pyramid));
  equations_.setModel(raycast_.depthBuffer(), raycast_.normalBuffer(), model_intrinsics,
                      T_W_C_guess);

  TrackResult result;
  result.raycast_ms = raycast_ms;
  const AssociationGates gates = gatesFor();
  Eigen::Isometry3d T_W_C = T_W_C_guess;
  double ms = 0.0;
  for (int level = config_.levels - 1; level >= 0; --level) {
    for (int i = 0; i < config_.iterations[static_cast<std::size_t>(level)]; ++i) {
      NormalEquations sums = equations_.run(level, T_W_C, gates, &ms);
      if (photometric) {
        sums = addWeighted(sums,
                           photometricEquations(pyramid[static_cast<std::size_t>(level)],
                                                live_intensity[static_cast<std::size_t>(level)],
                                                model_intensity, T_W_C, photo_gates),
                           color_weight);
      }
      result.equations_ms += ms;
      ++result.iterations;
      const GaussNewtonStep step = solveGaussNewton(sums, config_.min_eigenvalue);
      if (!step.solved) break;  // this level cannot constrain the pose; try the finer one
      T_W_C = applyIncrement(T_W_C, step.xi);
      if (step.xi.norm() < config_.convergence_update) break;
    }
  }
  // The figures of the final pose (the failure rules judge these; the conditioning with the
  // photometric rows, which constrain what the geometry leaves loose).
  const NormalEquations final_sums = equations_.run(0, T_W_C, gates, &ms);
  const NormalEquations final_photometric =
      photometric ? photometricEquations(pyramid[0], live_intensity[0], model_intensity, T_W_C,
                                         photo_gates)
                  : NormalEquations{};
  const NormalEquations final_system =
      photometric ? addWeighted(final_sums, final_photometric, color_weight) : final_sums;
  result.equations_ms += ms;
  result.T_W_C = T_W_C;
  result.inliers = final_sums.inliers;
  result.valid_pixels = pyramid[0].valid;
  result.inlier_fraction = static_cast<double>(final_sums.inliers) / pyramid[0].valid;
  result.rms_m =
      final_sums.inliers > 0 ? std::sqrt(final_sums.residual_sq / final_sums.inliers) : 0.0;
  result.min_eigenvalue = solveGaussNewton(final_system).min_eigenvalue;
  result.covariance =
      config_.covariance_scale *
      poseCovariance(final_system,
                     static_cast<double>(final_sums.inliers) + final_photometric.inliers);
  result.translation_sigma_m = std::sqrt(largestEigenvalue(result.covariance.topLeftCorner<3, 3>()));
  result.rotation_sigma_deg =
      std::sqrt(largestEigenvalue(result.covariance.bottomRightCorner<3, 3>())) * 180.0 / M_PI;
  judge(T_W_C_guess, &result);
  return finish(result);
}

void RgbdTracker::judge(const Eigen::Isometry3d& T_W_C_guess, TrackResult* r) const {
  std::ostringstream why;
  const Eigen::Isometry3d jump = T_W_C_guess.inverse() * r->T_W_C;
  if (r->inliers < config_.min_inliers) {
    why << "too few inliers (" << r->inliers << " < " << config_.min_inliers << ")";
  } else if (r->inlier_fraction < config_.min_inlier_fraction) {
    why << "inlier fraction " << r->inlier_fraction << " < " << config_.min_inlier_fraction;
  } else if (r->rms_m > config_.max_rms_m) {
    why << "residual RMS " << r->rms_m << " m > " << config_.max_rms_m << " m";
  } else if (r->min_eigenvalue < config_.min_eigenvalue) {
    why << "ill-conditioned: smallest eigenvalue " << r->min_eigenvalue << " < "
        << config_.min_eigenvalue;
  } else if (jump.translation().norm() > config_.max_translation_jump_m) {
    why << "jump of " << jump.translation().norm() << " m from the guess";
  } else if (rotationAngleDeg(jump) > config_.max_rotation_jump_deg) {
    why << "jump of " << rotationAngleDeg(jump) << " deg from the guess";
  }
  r->reason = why.str();
  r->status = r->reason.empty() ? TrackStatus::kOk : TrackStatus::kLost;
}

Eigen::Isometry3d MotionModel::predict() const {
  return has_velocity_ ? last_T_W_C_ * velocity_ : last_T_W_C_;
}

void MotionModel::accept(const Eigen::Isometry3d& T_W_C) {
  if (initialised_ && !after_loss_) {
    velocity_ = last_T_W_C_.inverse() * T_W_C;
    has_velocity_ = true;
  }
  last_T_W_C_ = T_W_C;
  initialised_ = true;
  after_loss_ = false;
}

void MotionModel::lost() {
  // NOTE: retry from the last good pose: extrapolating a motion that just failed compounds it.
  has_velocity_ = false;
  after_loss_ = true;
  velocity_ = Eigen::Isometry3d::Identity();
}

}  // namespace strata
