// Batched visibility-graph shortcutting (contract in path_shortcut.h).
#include "strata/plan/path_shortcut.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "strata/plan/plan_types.h"

namespace strata::plan {
namespace {

/// The polyline with extra vertices so that it has about `max_vertices` (the input's vertices
/// are kept).
std::vector<Eigen::Vector3f> densify(const std::vector<Eigen::Vector3f>& path_W, int max_vertices) {
  const double length_m = pathLength(path_W);
  const int budget = std::max(2, max_vertices - static_cast<int>(path_W.size()));
  const double spacing_m = length_m / budget;
  std::vector<Eigen::Vector3f> out{path_W.front()};
  for (std::size_t i = 1; i < path_W.size(); ++i) {
    const Eigen::Vector3f a = path_W[i - 1];
    const Eigen::Vector3f b = path_W[i];
    const int n =
        spacing_m > 0.0 ? std::max(1, static_cast<int>(std::ceil((b - a).norm() / spacing_m))) : 1;
    for (int k = 1; k <= n; ++k) out.push_back(a + (b - a) * (static_cast<float>(k) / n));
  }
  return out;
}

/// Shortest path from vertex 0 to the last one over the free pairs (visible[i][j - i - 1] for
/// j > i); empty when the last vertex cannot be reached.
std::vector<Eigen::Vector3f> shortestVisiblePath(const std::vector<Eigen::Vector3f>& v,
                                                 const std::vector<std::vector<char>>& visible) {
  const std::size_t n = v.size();
  std::vector<double> best(n, std::numeric_limits<double>::infinity());
  std::vector<std::size_t> from(n, 0);
  best[0] = 0.0;
  for (std::size_t j = 1; j < n; ++j) {
    for (std::size_t i = 0; i < j; ++i) {
      if (!visible[i][j - i - 1]) continue;
      const double d = best[i] + (v[j] - v[i]).norm();
      if (d < best[j]) {
        best[j] = d;
        from[j] = i;
      }
    }
  }
  std::vector<Eigen::Vector3f> out;
  if (!std::isfinite(best[n - 1])) return out;
  for (std::size_t j = n - 1;; j = from[j]) {
    out.push_back(v[j]);
    if (j == 0) break;
  }
  std::reverse(out.begin(), out.end());
  return out;
}

/// One round: densify, test every pair in one batch, keep the shortest visible path (the input
/// when the densified polyline's own pieces do not all pass: they are sampled at other points than
/// the input's segments).
std::vector<Eigen::Vector3f> shortcutRound(const std::vector<Eigen::Vector3f>& path_W,
                                           CollisionChecker& checker, float radius_m,
                                           UnknownPolicy unknown, int max_vertices,
                                           ShortcutStats& stats) {
  const std::vector<Eigen::Vector3f> v = densify(path_W, max_vertices);
  std::vector<EsdfSegment> candidates;
  for (std::size_t i = 0; i < v.size(); ++i) {
    for (std::size_t j = i + 1; j < v.size(); ++j) candidates.push_back({v[i], v[j]});
  }
  const std::vector<std::uint8_t> free = checker.segmentsFree(candidates, radius_m, unknown);
  stats.segments += candidates.size();
  ++stats.batches;
  std::vector<std::vector<char>> visible(v.size());
  std::size_t k = 0;
  for (std::size_t i = 0; i < v.size(); ++i) {
    for (std::size_t j = i + 1; j < v.size(); ++j) visible[i].push_back(free[k++] != 0);
  }
  std::vector<Eigen::Vector3f> out = shortestVisiblePath(v, visible);
  return out.empty() ? path_W : out;
}

/// Drops vertices that lie on the straight line of their neighbours (within 1e-5 m).
std::vector<Eigen::Vector3f> dropCollinear(const std::vector<Eigen::Vector3f>& path_W) {
  std::vector<Eigen::Vector3f> out{path_W.front()};
  for (std::size_t i = 1; i + 1 < path_W.size(); ++i) {
    const Eigen::Vector3f a = out.back();
    const Eigen::Vector3f b = path_W[i + 1];
    const Eigen::Vector3f ab = b - a;
    const float t = ab.squaredNorm() > 0.0f ? (path_W[i] - a).dot(ab) / ab.squaredNorm() : 0.0f;
    if (t > 0.0f && t < 1.0f && (a + ab * t - path_W[i]).norm() < 1e-5f) continue;
    out.push_back(path_W[i]);
  }
  out.push_back(path_W.back());
  return out;
}

}  // namespace

std::vector<Eigen::Vector3f> shortcutPath(const std::vector<Eigen::Vector3f>& path_W,
                                          CollisionChecker& checker, float radius_m,
                                          UnknownPolicy unknown, const ShortcutOptions& options,
                                          ShortcutStats* stats) {
  ShortcutStats local;
  ShortcutStats& s = stats != nullptr ? *stats : local;
  s = {};
  if (path_W.size() < 2 || options.rounds <= 0) return path_W;
  std::vector<Eigen::Vector3f> path = path_W;
  double length_m = pathLength(path);
  for (int round = 0; round < options.rounds; ++round) {
    std::vector<Eigen::Vector3f> shorter =
        shortcutRound(path, checker, radius_m, unknown, options.max_vertices, s);
    ++s.rounds;
    const double shorter_m = pathLength(shorter);
    const bool gained = shorter_m < length_m - 1e-4 * std::max(1.0, length_m);
    if (shorter_m <= length_m) path = std::move(shorter);
    length_m = std::min(length_m, shorter_m);
    if (!gained) break;
  }
  // Every segment of `path` passed (the same segment, the same samples). Merging collinear pieces
  // makes segments sampled at other points: the merged polyline is checked as a whole.
  std::vector<Eigen::Vector3f> merged = dropCollinear(path);
  if (merged.size() == path.size()) return path;
  ++s.batches;
  return checker.pathFree(merged, radius_m, unknown) ? merged : path;
}

}  // namespace strata::plan
