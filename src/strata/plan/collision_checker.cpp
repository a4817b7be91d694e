// Batched collision checks on the ESDF (contract in collision_checker.h).
#include "strata/plan/collision_checker.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "strata/esdf/esdf.h"
#include "strata/plan/plan_types.h"

namespace strata::plan {
namespace {

// Longer segments (in half voxels) are refused rather than sampled: beyond any map.
constexpr float kMaxSegmentSamples = 1 << 22;

/// Pieces of one capsule: the segment cut into n pieces of at most half a voxel; 0 when refused
/// (non-finite ends, too long).
int capsulePieces(const EsdfSegment& s, float voxel_size_m) {
  if (!s.a_W.allFinite() || !s.b_W.allFinite()) return 0;
  const float samples = std::ceil((s.b_W - s.a_W).norm() / (0.5f * voxel_size_m));
  if (!(samples < kMaxSegmentSamples)) return 0;
  return std::max(1, static_cast<int>(samples));
}

}  // namespace

double pathLength(const std::vector<Eigen::Vector3f>& path_W) {
  double length_m = 0.0;
  for (std::size_t i = 1; i < path_W.size(); ++i) length_m += (path_W[i] - path_W[i - 1]).norm();
  return length_m;
}

std::vector<std::uint8_t> CollisionChecker::segmentsFree(const std::vector<EsdfSegment>& segments,
                                                         float radius_m, UnknownPolicy unknown) {
  std::vector<std::uint8_t> out(segments.size(), 0);
  if (!(radius_m >= 0.0f)) return out;
  // Every sample gets the radius of the longest allowed piece, h = half a voxel: one radius, so
  // every sample of every segment goes in one batch (one dispatch on the device).
  const float h = 0.5f * voxelSize();
  const float sample_radius_m = std::sqrt(radius_m * radius_m + 0.25f * h * h);
  std::vector<Eigen::Vector3f> centres;
  std::vector<std::size_t> first_sample(segments.size() + 1, 0);
  std::vector<int> pieces(segments.size(), 0);
  for (std::size_t i = 0; i < segments.size(); ++i) {
    first_sample[i] = centres.size();
    pieces[i] = capsulePieces(segments[i], voxelSize());
    for (int k = 0; k <= pieces[i] && pieces[i] > 0; ++k) {
      const float t = static_cast<float>(k) / static_cast<float>(pieces[i]);
      centres.push_back(segments[i].a_W + (segments[i].b_W - segments[i].a_W) * t);
    }
  }
  first_sample[segments.size()] = centres.size();
  const std::vector<std::uint8_t> free = spheresFree(centres, sample_radius_m, unknown);
  for (std::size_t i = 0; i < segments.size(); ++i) {
    if (pieces[i] == 0) continue;
    const auto begin = free.begin() + static_cast<std::ptrdiff_t>(first_sample[i]);
    const auto end = free.begin() + static_cast<std::ptrdiff_t>(first_sample[i + 1]);
    out[i] = std::all_of(begin, end, [](std::uint8_t f) { return f != 0; }) ? 1 : 0;
  }
  return out;
}

bool CollisionChecker::segmentFree(const Eigen::Vector3f& a_W, const Eigen::Vector3f& b_W,
                                   float radius_m, UnknownPolicy unknown) {
  return segmentsFree({EsdfSegment{a_W, b_W}}, radius_m, unknown)[0] != 0;
}

bool CollisionChecker::pathFree(const std::vector<Eigen::Vector3f>& path_W, float radius_m,
                                UnknownPolicy unknown) {
  if (path_W.empty()) return true;
  if (path_W.size() == 1) return spheresFree(path_W, radius_m, unknown)[0] != 0;
  std::vector<EsdfSegment> segments;
  for (std::size_t i = 1; i < path_W.size(); ++i) segments.push_back({path_W[i - 1], path_W[i]});
  const std::vector<std::uint8_t> free = segmentsFree(segments, radius_m, unknown);
  return std::all_of(free.begin(), free.end(), [](std::uint8_t f) { return f != 0; });
}

float CollisionChecker::minClearance(const std::vector<Eigen::Vector3f>& path_W) {
  std::vector<Eigen::Vector3f> points;
  const float step_m = 0.5f * voxelSize();
  for (std::size_t i = 0; i < path_W.size(); ++i) {
    if (i == 0) {
      points.push_back(path_W[0]);
      continue;
    }
    const Eigen::Vector3f a = path_W[i - 1];
    const Eigen::Vector3f b = path_W[i];
    const int n = std::max(1, static_cast<int>(std::ceil((b - a).norm() / step_m)));
    for (int k = 1; k <= n; ++k) points.push_back(a + (b - a) * (static_cast<float>(k) / n));
  }
  if (points.empty()) return 0.0f;
  float clearance_m = std::numeric_limits<float>::infinity();
  for (const EsdfSample& s : sample(points)) {
    clearance_m = std::min(clearance_m, s.status == EsdfStatus::kKnown ? s.distance_m : 0.0f);
  }
  return clearance_m;
}

HostCollisionChecker::HostCollisionChecker(const EsdfMap& esdf) : query_(esdf) {}

std::vector<std::uint8_t> HostCollisionChecker::spheresFree(
    const std::vector<Eigen::Vector3f>& centres_W, float radius_m, UnknownPolicy unknown) {
  spheres_tested_ += centres_W.size();
  return query_.isSphereFree(centres_W, radius_m, 0.0f, unknown);
}

std::vector<EsdfSample> HostCollisionChecker::sample(const std::vector<Eigen::Vector3f>& points_W) {
  return query_.sample(points_W);
}

DeviceCollisionChecker::DeviceCollisionChecker(vk::Context& context, DeviceEsdf& esdf)
    : kernel_(context), esdf_(&esdf) {}

std::vector<std::uint8_t> DeviceCollisionChecker::spheresFree(
    const std::vector<Eigen::Vector3f>& centres_W, float radius_m, UnknownPolicy unknown) {
  spheres_tested_ += centres_W.size();
  EsdfQueryResult result = kernel_.run(*esdf_, centres_W, EsdfSphereTest{radius_m, 0.0f, unknown});
  device_ms_ += result.device_ms;
  return std::move(result.sphere_free);
}

std::vector<EsdfSample> DeviceCollisionChecker::sample(
    const std::vector<Eigen::Vector3f>& points_W) {
  EsdfQueryResult result = kernel_.run(*esdf_, points_W);
  device_ms_ += result.device_ms;
  return std::move(result.samples);
}

float DeviceCollisionChecker::voxelSize() const { return esdf_->tsdf().config().voxel_size_m; }

float DeviceCollisionChecker::maxDistance() const { return esdf_->config().max_distance_m; }

}  // namespace strata::plan
