// FPFH correspondences and RANSAC between two keyframe surfaces.
#include "strata/align/internal/surface_registration.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <limits>
#include <random>
#include <utility>
#include <vector>

namespace strata::align::detail {
namespace {

constexpr unsigned kSeed = 1;

float squaredDistance(const Fpfh& x, const Fpfh& y) {
  float sum = 0.0f;
  for (std::size_t i = 0; i < x.size(); ++i) sum += (x[i] - y[i]) * (x[i] - y[i]);
  return sum;
}

std::vector<int> nearest(const std::vector<Fpfh>& from, const std::vector<Fpfh>& to) {
  std::vector<int> out(from.size(), -1);
  for (std::size_t i = 0; i < from.size(); ++i) {
    float best = std::numeric_limits<float>::infinity();
    for (std::size_t j = 0; j < to.size(); ++j) {
      const float d = squaredDistance(from[i], to[j]);
      if (d < best) best = d, out[i] = static_cast<int>(j);
    }
  }
  return out;
}

// (index in a, index in b) of mutual nearest neighbours.
std::vector<std::pair<int, int>> mutualMatches(const KeyframeSurface& a, const KeyframeSurface& b) {
  const std::vector<int> b_to_a = nearest(b.fpfh, a.fpfh), a_to_b = nearest(a.fpfh, b.fpfh);
  std::vector<std::pair<int, int>> out;
  for (std::size_t j = 0; j < b_to_a.size(); ++j) {
    const int i = b_to_a[j];
    if (i >= 0 && a_to_b[static_cast<std::size_t>(i)] == static_cast<int>(j))
      out.emplace_back(i, static_cast<int>(j));
  }
  return out;
}

Eigen::Isometry3d fit(const KeyframeSurface& a, const KeyframeSurface& b,
                      const std::vector<std::pair<int, int>>& matches,
                      const std::vector<int>& use) {
  const auto n = static_cast<Eigen::Index>(use.size());
  Eigen::Matrix3Xd src(3, n), dst(3, n);
  for (Eigen::Index k = 0; k < n; ++k) {
    const auto& [i, j] = matches[static_cast<std::size_t>(use[static_cast<std::size_t>(k)])];
    src.col(k) = b.keypoints_C_m[static_cast<std::size_t>(j)].cast<double>();
    dst.col(k) = a.keypoints_C_m[static_cast<std::size_t>(i)].cast<double>();
  }
  return Eigen::Isometry3d(Eigen::umeyama(src, dst, false));
}

std::vector<int> inliersOf(const KeyframeSurface& a, const KeyframeSurface& b,
                           const std::vector<std::pair<int, int>>& matches,
                           const Eigen::Isometry3d& T_a_b, double inlier_m) {
  std::vector<int> out;
  const double gate = inlier_m * inlier_m;
  for (std::size_t k = 0; k < matches.size(); ++k) {
    const auto& [i, j] = matches[k];
    const Eigen::Vector3d d = a.keypoints_C_m[static_cast<std::size_t>(i)].cast<double>() -
                              T_a_b * b.keypoints_C_m[static_cast<std::size_t>(j)].cast<double>();
    if (d.squaredNorm() < gate) out.push_back(static_cast<int>(k));
  }
  return out;
}

// The triple's edges agree between the clouds and none is degenerate.
bool consistentTriple(const KeyframeSurface& a, const KeyframeSurface& b,
                      const std::vector<std::pair<int, int>>& matches, const int (&t)[3],
                      const SurfaceRegistrationConfig& config) {
  for (int e = 0; e < 3; ++e) {
    const auto& [i0, j0] = matches[static_cast<std::size_t>(t[e])];
    const auto& [i1, j1] = matches[static_cast<std::size_t>(t[(e + 1) % 3])];
    const double da = (a.keypoints_C_m[static_cast<std::size_t>(i0)] -
                       a.keypoints_C_m[static_cast<std::size_t>(i1)]).norm();
    const double db = (b.keypoints_C_m[static_cast<std::size_t>(j0)] -
                       b.keypoints_C_m[static_cast<std::size_t>(j1)]).norm();
    if (std::min(da, db) < config.min_edge_m) return false;
    if (std::min(da, db) < config.edge_similarity * std::max(da, db)) return false;
  }
  return true;
}

}  // namespace

SurfaceRegistration registerSurfaces(const KeyframeSurface& a, const KeyframeSurface& b,
                                     const SurfaceRegistrationConfig& config) {
  SurfaceRegistration result;
  const std::vector<std::pair<int, int>> matches = mutualMatches(a, b);
  result.correspondences = static_cast<int>(matches.size());
  if (matches.size() < 3) return result;
  std::mt19937 rng(kSeed);
  std::uniform_int_distribution<int> pick(0, static_cast<int>(matches.size()) - 1);
  std::vector<int> best;
  for (int it = 0; it < config.iterations; ++it) {
    const int t[3] = {pick(rng), pick(rng), pick(rng)};
    if (t[0] == t[1] || t[1] == t[2] || t[0] == t[2]) continue;
    if (!consistentTriple(a, b, matches, t, config)) continue;
    const Eigen::Isometry3d T = fit(a, b, matches, {t[0], t[1], t[2]});
    if (!T.matrix().allFinite()) continue;
    std::vector<int> inliers = inliersOf(a, b, matches, T, config.inlier_m);
    if (inliers.size() > best.size()) best = std::move(inliers);
  }
  if (best.size() < 3) return result;
  // Refit on the inliers twice: the set grows or shrinks a little with the better fit.
  for (int round = 0; round < 2; ++round) {
    const Eigen::Isometry3d T = fit(a, b, matches, best);
    if (!T.matrix().allFinite()) return result;
    std::vector<int> inliers = inliersOf(a, b, matches, T, config.inlier_m);
    result.T_a_b = T;
    if (inliers.size() < 3) return result;
    best = std::move(inliers);
  }
  result.found = true;
  result.inliers = static_cast<int>(best.size());
  return result;
}

}  // namespace strata::align::detail
