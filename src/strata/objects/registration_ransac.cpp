#include "strata/objects/internal/registration_ransac.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <random>
#include "strata/core/math_constants.h"

namespace strata::objects {

namespace {

/// Hypotheses closer than this (rotation, translation in voxels) are one.
constexpr double kDistinctAngleDeg = 10.0;
constexpr float kDistinctTranslationVoxels = 2.0f;
constexpr int kMinYawInliers = 6;

double rotationAngleDeg(const Eigen::Matrix3f& R) {
  const double c = std::clamp((static_cast<double>(R.trace()) - 1.0) / 2.0, -1.0, 1.0);
  return std::acos(c) * 180.0 / kPi;
}

bool sameHypothesis(const Eigen::Matrix4f& a, const Eigen::Matrix4f& b, float voxel_m) {
  const Eigen::Matrix3f relative = a.topLeftCorner<3, 3>().transpose() * b.topLeftCorner<3, 3>();
  return rotationAngleDeg(relative) < kDistinctAngleDeg &&
         (a.topRightCorner<3, 1>() - b.topRightCorner<3, 1>()).norm() <
             kDistinctTranslationVoxels * voxel_m;
}

/// Polygon test (as PCL's CorrespondenceRejectorPoly): every edge of the sample has about the
/// same length on both sides, and none is so short that the fit is ill-conditioned.
bool edgesAgree(const std::vector<Eigen::Vector3f>& s, const std::vector<Eigen::Vector3f>& t,
                float similarity, float min_edge_m) {
  for (std::size_t i = 0; i < s.size(); ++i) {
    for (std::size_t j = i + 1; j < s.size(); ++j) {
      const float ds = (s[i] - s[j]).norm();
      const float dt = (t[i] - t[j]).norm();
      if (std::min(ds, dt) < min_edge_m || std::min(ds, dt) < similarity * std::max(ds, dt)) {
        return false;
      }
    }
  }
  return true;
}

Eigen::Matrix4f fitRigid(const std::vector<Eigen::Vector3f>& s,
                         const std::vector<Eigen::Vector3f>& t) {
  Eigen::Matrix3Xf src(3, s.size()), dst(3, t.size());
  for (std::size_t i = 0; i < s.size(); ++i) {
    src.col(static_cast<Eigen::Index>(i)) = s[i];
    dst.col(static_cast<Eigen::Index>(i)) = t[i];
  }
  return Eigen::umeyama(src, dst, false);
}

/// Least-squares rotation about z and translation taking `s` onto `t` (the 4-DoF analogue of
/// Umeyama): yaw from the summed cross and dot products of the centred horizontal offsets.
Eigen::Matrix4f fitYaw(const std::vector<Eigen::Vector3f>& s,
                       const std::vector<Eigen::Vector3f>& t) {
  Eigen::Vector3f cs = Eigen::Vector3f::Zero(), ct = Eigen::Vector3f::Zero();
  for (std::size_t i = 0; i < s.size(); ++i) {
    cs += s[i];
    ct += t[i];
  }
  cs /= static_cast<float>(s.size());
  ct /= static_cast<float>(t.size());
  double sine = 0.0, cosine = 0.0;
  for (std::size_t i = 0; i < s.size(); ++i) {
    const Eigen::Vector2d a = (s[i] - cs).head<2>().cast<double>();
    const Eigen::Vector2d b = (t[i] - ct).head<2>().cast<double>();
    sine += a.x() * b.y() - a.y() * b.x();
    cosine += a.dot(b);
  }
  const Eigen::Matrix3f R =
      Eigen::AngleAxisf(static_cast<float>(std::atan2(sine, cosine)), Eigen::Vector3f::UnitZ())
          .toRotationMatrix();
  Eigen::Matrix4f T = Eigen::Matrix4f::Identity();
  T.topLeftCorner<3, 3>() = R;
  T.topRightCorner<3, 1>() = ct - R * cs;
  return T;
}

/// The 2-point sample test of ransacYaw: both pairs need the same vertical shift (a yaw keeps
/// heights), the same horizontal distance on both sides, and enough of it to fix the yaw.
bool yawPairAgrees(const Eigen::Vector3f& s0, const Eigen::Vector3f& s1, const Eigen::Vector3f& t0,
                   const Eigen::Vector3f& t1, float inlier_m) {
  const float shift0 = t0.z() - s0.z();
  const float shift1 = t1.z() - s1.z();
  if (std::abs(shift0 - shift1) > inlier_m) return false;
  const float ds = (s1 - s0).head<2>().norm();
  const float dt = (t1 - t0).head<2>().norm();
  return std::min(ds, dt) >= 2.0f * inlier_m && std::abs(ds - dt) <= inlier_m;
}

std::vector<std::size_t> inliersOf(const Eigen::Matrix4f& T,
                                   const std::vector<Eigen::Vector3f>& source,
                                   const std::vector<Eigen::Vector3f>& target,
                                   const std::vector<Correspondence>& matches, float inlier_m) {
  const Eigen::Matrix3f R = T.topLeftCorner<3, 3>();
  const Eigen::Vector3f t = T.topRightCorner<3, 1>();
  std::vector<std::size_t> out;
  for (std::size_t i = 0; i < matches.size(); ++i) {
    const Eigen::Vector3f moved = R * source[static_cast<std::size_t>(matches[i].source)] + t;
    if ((moved - target[static_cast<std::size_t>(matches[i].target)]).squaredNorm() <=
        inlier_m * inlier_m) {
      out.push_back(i);
    }
  }
  return out;
}

/// Adds `h` to the best-first list `kept` (at most `keep`), merging it with a near duplicate.
void keepBest(std::vector<Hypothesis>& kept, const Hypothesis& h, std::size_t keep, float voxel_m) {
  for (Hypothesis& k : kept) {
    if (sameHypothesis(k.T, h.T, voxel_m)) {
      if (h.inliers > k.inliers) k = h;
      std::stable_sort(kept.begin(), kept.end(), [](const Hypothesis& a, const Hypothesis& b) {
        return a.inliers > b.inliers;
      });
      return;
    }
  }
  if (kept.size() == keep && h.inliers <= kept.back().inliers) return;
  kept.push_back(h);
  std::stable_sort(kept.begin(), kept.end(),
                   [](const Hypothesis& a, const Hypothesis& b) { return a.inliers > b.inliers; });
  if (kept.size() > keep) kept.pop_back();
}

/// Least-squares refit to the hypothesis' inliers, kept when it stays upright enough.
Hypothesis refit(const Hypothesis& h, const std::vector<Eigen::Vector3f>& source,
                 const std::vector<Eigen::Vector3f>& target,
                 const std::vector<Correspondence>& matches, const RegistrationConfig& config) {
  const float inlier_m = config.inlier_distance_voxels * config.voxel_size_m;
  std::vector<Eigen::Vector3f> s, t;
  for (std::size_t i : inliersOf(h.T, source, target, matches, inlier_m)) {
    s.push_back(source[static_cast<std::size_t>(matches[i].source)]);
    t.push_back(target[static_cast<std::size_t>(matches[i].target)]);
  }
  Hypothesis out = h;
  if (s.size() < 3) return out;
  out.T = config.four_dof ? fitYaw(s, t) : fitRigid(s, t);
  if (tiltDeg(out.T) > config.max_tilt_deg) return h;
  out.inliers = static_cast<int>(inliersOf(out.T, source, target, matches, inlier_m).size());
  return out.inliers >= h.inliers ? out : h;
}

}  // namespace

double tiltDeg(const Eigen::Matrix4f& T) {
  const double c = std::clamp(static_cast<double>(T(2, 2)), -1.0, 1.0);
  return std::acos(c) * 180.0 / kPi;
}

std::vector<Hypothesis> ransacUpright(const std::vector<Eigen::Vector3f>& source,
                                      const std::vector<Eigen::Vector3f>& target,
                                      const std::vector<Correspondence>& matches,
                                      const RegistrationConfig& config, std::size_t keep) {
  const auto samples = static_cast<std::size_t>(config.ransac_samples);
  std::vector<Hypothesis> kept;
  if (matches.size() < samples || keep == 0) return kept;
  const float inlier_m = config.inlier_distance_voxels * config.voxel_size_m;
  std::mt19937 rng(config.seed);
  std::uniform_int_distribution<std::size_t> pick(0, matches.size() - 1);
  std::vector<std::size_t> chosen(samples);
  std::vector<Eigen::Vector3f> s(samples), t(samples);
  for (int iteration = 0; iteration < config.ransac_iterations; ++iteration) {
    for (std::size_t k = 0; k < samples; ++k) {
      chosen[k] = pick(rng);
      s[k] = source[static_cast<std::size_t>(matches[chosen[k]].source)];
      t[k] = target[static_cast<std::size_t>(matches[chosen[k]].target)];
    }
    if (!edgesAgree(s, t, config.edge_similarity, 2.0f * inlier_m)) continue;
    Hypothesis h;
    h.T = fitRigid(s, t);
    if (tiltDeg(h.T) > config.max_tilt_deg) continue;
    h.inliers = static_cast<int>(inliersOf(h.T, source, target, matches, inlier_m).size());
    if (h.inliers <= static_cast<int>(samples)) continue;  // only the sample itself agrees
    keepBest(kept, h, keep, config.voxel_size_m);
  }
  for (Hypothesis& h : kept) h = refit(h, source, target, matches, config);
  return kept;
}

std::vector<Hypothesis> ransacYaw(const std::vector<Eigen::Vector3f>& source,
                                  const std::vector<Eigen::Vector3f>& target,
                                  const std::vector<Correspondence>& matches,
                                  const RegistrationConfig& config, std::size_t keep) {
  std::vector<Hypothesis> kept;
  if (matches.size() < 2 || keep == 0) return kept;
  const float inlier_m = config.inlier_distance_voxels * config.voxel_size_m;
  std::mt19937 rng(config.seed);
  std::uniform_int_distribution<std::size_t> pick(0, matches.size() - 1);
  std::vector<Eigen::Vector3f> s(2), t(2);
  for (int iteration = 0; iteration < config.ransac_iterations; ++iteration) {
    const Correspondence& a = matches[pick(rng)];
    const Correspondence& b = matches[pick(rng)];
    s[0] = source[static_cast<std::size_t>(a.source)];
    s[1] = source[static_cast<std::size_t>(b.source)];
    t[0] = target[static_cast<std::size_t>(a.target)];
    t[1] = target[static_cast<std::size_t>(b.target)];
    if (!yawPairAgrees(s[0], s[1], t[0], t[1], inlier_m)) continue;
    Hypothesis h;
    h.T = fitYaw(s, t);
    h.inliers = static_cast<int>(inliersOf(h.T, source, target, matches, inlier_m).size());
    // A pose that fewer correspondences support than ICP needs pairs (6) is not one: a handful
    // of points (a sliver of a segment) agrees with itself under any yaw.
    if (h.inliers < kMinYawInliers) continue;
    keepBest(kept, h, keep, config.voxel_size_m);
  }
  for (Hypothesis& h : kept) h = refit(h, source, target, matches, config);
  return kept;
}

}  // namespace strata::objects
