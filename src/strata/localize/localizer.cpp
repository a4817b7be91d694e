// Localisation of a live frame against the prior map: candidates, verification, agreement.
#include "strata/localize/localizer.h"

#include <algorithm>
#include <Eigen/Eigenvalues>
#include <chrono>
#include <cmath>
#include <vector>

#include "strata/core/error.h"

namespace strata::localize {
namespace {

using Clock = std::chrono::steady_clock;

struct Candidate {
  std::size_t keyframe = 0;
  const char* source = "";
};

bool taken(const std::vector<Candidate>& candidates, std::size_t keyframe) {
  return std::any_of(candidates.begin(), candidates.end(),
                     [&](const Candidate& c) { return c.keyframe == keyframe; });
}

double rotationAngle(const Eigen::Matrix3d& R) {
  return Eigen::AngleAxisd(R).angle();
}

/// The map keyframes near the prior, nearest first, that look roughly the same way.
std::vector<std::size_t> nearPrior(const PriorMap& map, const PosePrior& prior,
                                   const LocalizerConfig& config) {
  std::vector<std::pair<double, std::size_t>> near;
  const Eigen::Vector3d p = prior.T_W_C.translation();
  const Eigen::Vector3d z = prior.T_W_C.linear().col(2);
  for (std::size_t k = 0; k < map.keyframes().size(); ++k) {
    const Eigen::Isometry3d& T = map.keyframes()[k].T_W_C;
    const double d = (T.translation() - p).norm();
    if (d > config.prior_radius_m) continue;
    const double angle = std::acos(std::clamp(T.linear().col(2).dot(z), -1.0, 1.0));
    if (angle > config.prior_max_angle_rad) continue;
    // Distance plus the angle weighted as 1 m per radian: a keyframe looking the same way a
    // little farther off shares more of the view than a near one turned away.
    near.emplace_back(d + angle, k);
  }
  std::sort(near.begin(), near.end());
  std::vector<std::size_t> out;
  for (const auto& [score, k] : near) out.push_back(k);
  return out;
}

}  // namespace

void LocalizerConfig::validate() const {
  verify.validate();
  if (appearance_candidates + surface_candidates + prior_candidates == 0)
    throw InputError("localizer: every candidate source is off");
  if (min_votes < 1) throw InputError("localizer: min_votes must be >= 1");
  if (!(prior_radius_m > 0.0)) throw InputError("localizer: prior_radius_m must be > 0");
  if (!(prior_max_angle_rad > 0.0)) throw InputError("localizer: prior_max_angle_rad must be > 0");
  if (!(max_disagreement_m > 0.0) || !(max_disagreement_rad > 0.0))
    throw InputError("localizer: max_disagreement_m and _rad must be > 0");
  if (enough_accepted < 1) throw InputError("localizer: enough_accepted must be >= 1");
}

Localizer::Localizer(const PriorMap& map, const LocalizerConfig& config)
    : map_(map), config_(config) {
  config_.validate();
}

Localization Localizer::localize(const ColorImage& color, const DepthImage& depth,
                                 const CameraIntrinsics& intrinsics,
                                 const std::optional<PosePrior>& prior) const {
  const auto start = Clock::now();
  const auto since = [](Clock::time_point t) {
    return std::chrono::duration<double, std::milli>(Clock::now() - t).count();
  };
  Localization out;
  const PriorMapConfig& map_config = map_.config();
  if (depth.width_px != intrinsics.width_px || depth.height_px != intrinsics.height_px)
    throw InputError("localize: the depth image's size disagrees with the intrinsics");
  auto step = Clock::now();
  align::KeyframeFeatures features;
  if (!color.empty()) features = align::extractFeatures(color, depth, intrinsics, map_config.features);
  out.features_ms = since(step);

  // Pass 1, appearance (ORB, PnP, ICP): the keyframes near the prior first (cheapest to confirm
  // when the odometry is good), then the place index's.
  std::vector<Candidate> candidates;
  if (prior && config_.prior_candidates > 0) {
    for (std::size_t k : nearPrior(map_, *prior, config_)) {
      if (candidates.size() >= config_.prior_candidates) break;
      candidates.push_back({k, "prior"});
    }
  }
  if (features.size() > 0 && config_.appearance_candidates > 0) {
    for (const align::PlaceCandidate& c :
         map_.index().query(features, config_.appearance_candidates, config_.min_votes,
                            [](std::size_t) { return true; })) {
      if (!taken(candidates, c.keyframe)) candidates.push_back({c.keyframe, "appearance"});
    }
  }

  struct Accepted {
    std::size_t candidate = 0;
    align::LoopMeasurement m;
    Eigen::Isometry3d T_W_C;
  };
  std::vector<Accepted> accepted;
  std::string last_reason;
  const auto verify = [&](std::size_t first, const align::KeyframeSurface* live_surface) {
    step = Clock::now();
    const align::VerifyKeyframe live{&features, &depth, intrinsics, live_surface};
    for (std::size_t c = first; c < candidates.size(); ++c) {
      if (accepted.size() >= config_.enough_accepted) break;
      const MapKeyframe& k = map_.keyframes()[candidates[c].keyframe];
      const align::VerifyKeyframe a{&k.features, &k.depth, k.intrinsics,
                                    live_surface && k.surface.size() > 0 ? &k.surface : nullptr};
      ++out.candidates;
      align::LoopMeasurement m = align::verifyLoop(a, live, config_.verify);
      if (!m.accepted) {
        last_reason = m.reason;
        continue;
      }
      accepted.push_back({c, m, k.T_W_C * m.T_a_b});
    }
    out.verify_ms += since(step);
  };
  verify(0, nullptr);

  // Pass 2, only when appearance verified nothing: the surface (FPFH RANSAC, ICP) against the
  // prior's keyframes again and the keyframes nearest by surface descriptor.
  align::KeyframeSurface surface;
  if (accepted.empty() && map_config.surfaces && config_.surface_candidates > 0) {
    step = Clock::now();
    surface = align::describeSurface(depth, intrinsics, map_config.surface);
    out.surface_ms = since(step);
    const std::size_t first = candidates.size();
    std::vector<Candidate> second;
    for (const Candidate& c : candidates)
      if (std::string(c.source) == "prior") second.push_back(c);
    if (!surface.global.empty()) {
      std::vector<std::pair<double, std::size_t>> nearest;
      for (std::size_t k = 0; k < map_.keyframes().size(); ++k) {
        if (taken(second, k)) continue;
        const double d = align::surfaceDistance(surface, map_.keyframes()[k].surface);
        if (std::isfinite(d)) nearest.emplace_back(d, k);
      }
      const std::size_t n = std::min(config_.surface_candidates, nearest.size());
      std::partial_sort(nearest.begin(), nearest.begin() + static_cast<std::ptrdiff_t>(n),
                        nearest.end());
      for (std::size_t i = 0; i < n; ++i) second.push_back({nearest[i].second, "surface"});
    }
    candidates.insert(candidates.end(), second.begin(), second.end());
    if (surface.size() > 0) verify(first, &surface);
  }
  if (candidates.empty()) {
    out.reason = features.size() == 0 && surface.global.empty()
                     ? "no features and no surface to describe the frame"
                     : "no candidate keyframe (place index, surface or prior)";
    out.time_ms = since(start);
    return out;
  }
  out.accepted = accepted.size();
  if (accepted.empty()) {
    out.reason = "no candidate verified (" + std::to_string(out.candidates) +
                 " tried; last: " + last_reason + ")";
    out.time_ms = since(start);
    return out;
  }
  const auto best = std::max_element(accepted.begin(), accepted.end(),
                                     [](const Accepted& x, const Accepted& y) {
                                       return x.m.overlap < y.m.overlap;
                                     });
  for (const Accepted& other : accepted) {
    const Eigen::Isometry3d delta = best->T_W_C.inverse() * other.T_W_C;
    if (delta.translation().norm() > config_.max_disagreement_m ||
        rotationAngle(delta.linear()) > config_.max_disagreement_rad) {
      out.reason = "ambiguous: two verified keyframes disagree by " +
                   std::to_string(delta.translation().norm()) + " m";
      out.time_ms = since(start);
      return out;
    }
  }
  out.localized = true;
  out.T_W_C = best->T_W_C;
  out.keyframe = candidates[best->candidate].keyframe;
  out.candidate_source = candidates[best->candidate].source;
  out.inliers = best->m.inliers;
  out.residual_m = best->m.residual_m;
  out.overlap = best->m.overlap;
  out.from_surface = best->m.from_surface;
  // The verifier's information is of T_a_b perturbed on the right, which is T_W_C's too.
  const Eigen::Matrix<double, 6, 6> info = 0.5 * (best->m.information + best->m.information.transpose());
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix<double, 6, 6>> eigen(info);
  const Eigen::Matrix<double, 6, 1> values = eigen.eigenvalues().cwiseMax(1e-6);
  out.covariance = eigen.eigenvectors() * values.cwiseInverse().asDiagonal() *
                   eigen.eigenvectors().transpose();
  out.time_ms = since(start);
  return out;
}

}  // namespace strata::localize
