// Host ESDF queries: distance, gradient and status (semantics in esdf_query.h).
#include "strata/esdf/esdf_query.h"

#include <cmath>

#include "strata/esdf/internal/esdf_query_lookup.h"
#include "strata/core/parallel_for.h"

namespace strata {
namespace {

using esdf_query_detail::Lookup;

// Below this many points a batch runs on the calling thread: starting threads costs more.
constexpr std::size_t kParallelMinPoints = 4096;
constexpr std::size_t kChunkPoints = 1024;

Eigen::Vector3i corner(int i) { return Eigen::Vector3i(i & 1, (i >> 1) & 1, (i >> 2) & 1); }

float trilinear(const float v[8], const Eigen::Vector3f& f) {
  auto mix = [](float a, float b, float t) { return a * (1.0f - t) + b * t; };
  const float x00 = mix(v[0], v[1], f.x());
  const float x10 = mix(v[2], v[3], f.x());
  const float x01 = mix(v[4], v[5], f.x());
  const float x11 = mix(v[6], v[7], f.x());
  return mix(mix(x00, x10, f.y()), mix(x01, x11, f.y()), f.z());
}

/// Derivative of the trilinear interpolant with respect to f (voxel units).
Eigen::Vector3f trilinearGradient(const float v[8], const Eigen::Vector3f& f) {
  const float gx = (1 - f.y()) * (1 - f.z()) * (v[1] - v[0]) + f.y() * (1 - f.z()) * (v[3] - v[2]) +
                   (1 - f.y()) * f.z() * (v[5] - v[4]) + f.y() * f.z() * (v[7] - v[6]);
  const float gy = (1 - f.x()) * (1 - f.z()) * (v[2] - v[0]) + f.x() * (1 - f.z()) * (v[3] - v[1]) +
                   (1 - f.x()) * f.z() * (v[6] - v[4]) + f.x() * f.z() * (v[7] - v[5]);
  const float gz = (1 - f.x()) * (1 - f.y()) * (v[4] - v[0]) + f.x() * (1 - f.y()) * (v[5] - v[1]) +
                   (1 - f.x()) * f.y() * (v[6] - v[2]) + f.x() * f.y() * (v[7] - v[3]);
  return Eigen::Vector3f(gx, gy, gz);
}

EsdfSample samplePoint(Lookup& lookup, float voxel_size_m, const Eigen::Vector3f& p_W) {
  EsdfSample out;
  GlobalVoxelIndex own;
  if (!esdf_query_detail::voxelOf(p_W, voxel_size_m, &own)) return out;
  float own_distance_m = 0.0f;
  out.status = lookup.read(own, &own_distance_m);
  if (out.status != EsdfStatus::kKnown) return out;
  out.distance_m = own_distance_m;
  const Eigen::Vector3f g = p_W / voxel_size_m - Eigen::Vector3f::Constant(0.5f);
  const Eigen::Vector3f base_f = g.array().floor();
  const Eigen::Vector3i base = base_f.cast<int>();
  float values[8];
  for (int i = 0; i < 8; ++i) {
    if (lookup.read(base + corner(i), &values[i]) != EsdfStatus::kKnown) return out;
  }
  const Eigen::Vector3f f = g - base_f;
  out.distance_m = trilinear(values, f);
  out.gradient = trilinearGradient(values, f) / voxel_size_m;
  out.interpolated = true;
  return out;
}

}  // namespace

EsdfQuery::EsdfQuery(const EsdfMap& map) : map_(map) {}

EsdfSample EsdfQuery::sample(const Eigen::Vector3f& p_W) const {
  Lookup lookup(map_);
  return samplePoint(lookup, map_.voxel_size_m, p_W);
}

std::vector<EsdfSample> EsdfQuery::sample(const std::vector<Eigen::Vector3f>& points_W) const {
  std::vector<EsdfSample> out(points_W.size());
  const int threads = points_W.size() >= kParallelMinPoints ? resolveThreadCount(0) : 1;
  parallelForChunks(points_W.size(), threads, kChunkPoints,
                            [&](std::size_t begin, std::size_t end) {
                              Lookup lookup(map_);
                              for (std::size_t i = begin; i < end; ++i) {
                                out[i] = samplePoint(lookup, map_.voxel_size_m, points_W[i]);
                              }
                            });
  return out;
}

EsdfStatus EsdfQuery::status(const Eigen::Vector3f& p_W) const {
  GlobalVoxelIndex v;
  if (!esdf_query_detail::voxelOf(p_W, map_.voxel_size_m, &v)) return EsdfStatus::kOutside;
  Lookup lookup(map_);
  float unused = 0.0f;
  return lookup.read(v, &unused);
}

}  // namespace strata
