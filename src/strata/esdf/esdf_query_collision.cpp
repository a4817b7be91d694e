// Host ESDF collision queries: spheres, segments, paths (semantics in esdf_query.h).
#include <algorithm>
#include <cmath>

#include "strata/esdf/esdf_query.h"
#include "strata/esdf/internal/esdf_query_lookup.h"
#include "strata/core/parallel_for.h"

namespace strata {
namespace esdf_query_detail {
namespace {

/// Inclusive global voxel range of one block that a ball scan visits.
struct ScanBox {
  Eigen::Vector3i lo, hi;
};

bool isTarget(const EsdfVoxel& voxel, float voxel_size_m, ScanTarget target) {
  const bool observed = esdfObserved(voxel);
  if (target == ScanTarget::kUnknown) return !observed;
  return observed && voxel.distance_m < 0.5f * voxel_size_m;  // a site or inside
}

/// An unallocated block is unknown throughout: is its voxel centre nearest to c within reach?
bool missingBlockReaches(const ScanBox& box, float voxel_size_m, const Eigen::Vector3f& c,
                         float r2) {
  const Eigen::Vector3f g = c / voxel_size_m - Eigen::Vector3f::Constant(0.5f);
  const Eigen::Vector3i nearest =
      g.array().round().cast<int>().matrix().cwiseMax(box.lo).cwiseMin(box.hi);
  return (voxelCenter(nearest, voxel_size_m) - c).squaredNorm() <= r2;
}

bool blockContains(const EsdfBlock& block, const BlockIndex& b, const ScanBox& box,
                   float voxel_size_m, const Eigen::Vector3f& c, float r2, ScanTarget target) {
  for (int z = box.lo.z(); z <= box.hi.z(); ++z) {
    for (int y = box.lo.y(); y <= box.hi.y(); ++y) {
      for (int x = box.lo.x(); x <= box.hi.x(); ++x) {
        const Eigen::Vector3i v(x, y, z);
        if ((voxelCenter(v, voxel_size_m) - c).squaredNorm() > r2) continue;
        const Eigen::Vector3i l = v - b * kBlockEdge;
        if (isTarget(block[linearVoxelIndex(l.x(), l.y(), l.z())], voxel_size_m, target)) {
          return true;
        }
      }
    }
  }
  return false;
}

}  // namespace

bool ballContains(Lookup& lookup, float voxel_size_m, const Eigen::Vector3f& c, float radius_m,
                  ScanTarget target) {
  // Voxel indices whose centres (i + 0.5) * voxel lie within [c - r, c + r] on every axis.
  const Eigen::Array3f half = Eigen::Array3f::Constant(0.5f);
  const Eigen::Vector3i lo = ((c.array() - radius_m) / voxel_size_m - half).ceil().cast<int>();
  const Eigen::Vector3i hi = ((c.array() + radius_m) / voxel_size_m - half).floor().cast<int>();
  if ((lo.array() > hi.array()).any()) return false;
  const float r2 = radius_m * radius_m;
  const BlockIndex block_lo = blockOfVoxel(lo);
  const BlockIndex block_hi = blockOfVoxel(hi);
  for (int bz = block_lo.z(); bz <= block_hi.z(); ++bz) {
    for (int by = block_lo.y(); by <= block_hi.y(); ++by) {
      for (int bx = block_lo.x(); bx <= block_hi.x(); ++bx) {
        const BlockIndex b(bx, by, bz);
        const ScanBox box{lo.cwiseMax(b * kBlockEdge),
                          hi.cwiseMin(b * kBlockEdge + Eigen::Vector3i::Constant(kBlockEdge - 1))};
        const EsdfBlock* block = lookup.block(b);
        const bool found =
            block == nullptr
                ? target == ScanTarget::kUnknown && missingBlockReaches(box, voxel_size_m, c, r2)
                : blockContains(*block, b, box, voxel_size_m, c, r2, target);
        if (found) return true;
      }
    }
  }
  return false;
}

}  // namespace esdf_query_detail

namespace {

using esdf_query_detail::Lookup;
using esdf_query_detail::ScanTarget;

// Batches below this run on the calling thread (collision tests cost microseconds each).
constexpr std::size_t kParallelMinItems = 256;
constexpr std::size_t kChunkItems = 64;
// Longer segments (in half voxels) are refused rather than sampled: beyond any map.
constexpr float kMaxSegmentSamples = 1 << 22;

bool sphereFree(Lookup& lookup, const EsdfMap& map, const Eigen::Vector3f& c, float radius_m,
                UnknownPolicy policy) {
  // NOTE: written so that NaN radii fail (comparisons with NaN are false).
  if (!(radius_m >= 0.0f) || !(radius_m < map.config.max_distance_m)) return false;
  const float voxel_size_m = map.voxel_size_m;
  GlobalVoxelIndex v;
  if (!esdf_query_detail::voxelOf(c, voxel_size_m, &v)) return false;
  float distance_m = 0.0f;
  if (lookup.read(v, &distance_m) == EsdfStatus::kKnown) {
    // The ESDF is 1-Lipschitz: d(c) >= d(v) - |c - centre(v)|.
    const float clearance_m = distance_m - (c - voxelCenter(v, voxel_size_m)).norm();
    if (!(clearance_m > radius_m)) return false;
    return policy == UnknownPolicy::kFree ||
           !esdf_query_detail::ballContains(lookup, voxel_size_m, c, radius_m,
                                            ScanTarget::kUnknown);
  }
  if (policy == UnknownPolicy::kOccupied) return false;
  return !esdf_query_detail::ballContains(lookup, voxel_size_m, c, radius_m, ScanTarget::kObstacle);
}

bool segmentFree(Lookup& lookup, const EsdfMap& map, const Eigen::Vector3f& a,
                 const Eigen::Vector3f& b, float radius_m, UnknownPolicy policy) {
  if (!a.allFinite() || !b.allFinite() || !(radius_m >= 0.0f)) return false;
  const float samples = std::ceil((b - a).norm() / (0.5f * map.voxel_size_m));
  if (!(samples < kMaxSegmentSamples)) return false;
  const int n = std::max(1, static_cast<int>(samples));
  const float h = (b - a).norm() / static_cast<float>(n);
  // Every point of the capsule lies within this of some sample.
  const float sample_radius_m = std::sqrt(radius_m * radius_m + 0.25f * h * h);
  for (int i = 0; i <= n; ++i) {
    const Eigen::Vector3f s = a + (b - a) * (static_cast<float>(i) / static_cast<float>(n));
    if (!sphereFree(lookup, map, s, sample_radius_m, policy)) return false;
  }
  return true;
}

template <typename Item, typename Test>
std::vector<std::uint8_t> forEach(const std::vector<Item>& items, const EsdfMap& map, Test test) {
  std::vector<std::uint8_t> out(items.size(), 0);
  const int threads = items.size() >= kParallelMinItems ? resolveThreadCount(0) : 1;
  parallelForChunks(items.size(), threads, kChunkItems,
                            [&](std::size_t begin, std::size_t end) {
                              Lookup lookup(map);
                              for (std::size_t i = begin; i < end; ++i) {
                                out[i] = test(lookup, items[i]) ? 1 : 0;
                              }
                            });
  return out;
}

}  // namespace

bool EsdfQuery::isSphereFree(const Eigen::Vector3f& centre_W, float radius_m, float margin_m,
                             UnknownPolicy policy) const {
  Lookup lookup(map_);
  return sphereFree(lookup, map_, centre_W, radius_m + margin_m, policy);
}

std::vector<std::uint8_t> EsdfQuery::isSphereFree(const std::vector<Eigen::Vector3f>& centres_W,
                                                  float radius_m, float margin_m,
                                                  UnknownPolicy policy) const {
  return forEach(centres_W, map_, [&](Lookup& lookup, const Eigen::Vector3f& c) {
    return sphereFree(lookup, map_, c, radius_m + margin_m, policy);
  });
}

bool EsdfQuery::isSegmentFree(const Eigen::Vector3f& a_W, const Eigen::Vector3f& b_W,
                              float radius_m, UnknownPolicy policy) const {
  Lookup lookup(map_);
  return segmentFree(lookup, map_, a_W, b_W, radius_m, policy);
}

std::vector<std::uint8_t> EsdfQuery::isSegmentFree(const std::vector<EsdfSegment>& segments,
                                                   float radius_m, UnknownPolicy policy) const {
  return forEach(segments, map_, [&](Lookup& lookup, const EsdfSegment& s) {
    return segmentFree(lookup, map_, s.a_W, s.b_W, radius_m, policy);
  });
}

bool EsdfQuery::isPathFree(const std::vector<Eigen::Vector3f>& polyline_W, float radius_m,
                           UnknownPolicy policy) const {
  Lookup lookup(map_);
  if (polyline_W.size() == 1) return sphereFree(lookup, map_, polyline_W[0], radius_m, policy);
  for (std::size_t i = 1; i < polyline_W.size(); ++i) {
    if (!segmentFree(lookup, map_, polyline_W[i - 1], polyline_W[i], radius_m, policy)) {
      return false;
    }
  }
  return true;
}

}  // namespace strata
