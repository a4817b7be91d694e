#pragma once
// Internal to the host ESDF queries: voxel lookup with a one-block cache (one per thread, so the
// queries stay thread safe), and the ball scans of the collision tests. Mirrors the lookup and
// scan functions of shaders/esdf_query_points.comp.
#include <Eigen/Core>
#include <cmath>

#include "strata/esdf/esdf_query.h"

namespace strata::esdf_query_detail {

/// Voxels per axis beyond which a point is outside the block range (2^20 blocks of 8, with room).
inline constexpr float kMaxVoxelCoord = 8.0e6f;

/// The voxel holding p; false when p is not finite or beyond the block range.
inline bool voxelOf(const Eigen::Vector3f& p_W, float voxel_size_m, GlobalVoxelIndex* v) {
  const Eigen::Vector3f g = p_W / voxel_size_m;
  // NOTE: allFinite first: Eigen's maxCoeff may skip a NaN coefficient, and a NaN cast to int is
  // undefined behaviour (UndefinedBehaviorSanitizer found it on the NaN query points).
  if (!g.allFinite() || !(g.cwiseAbs().maxCoeff() < kMaxVoxelCoord)) return false;
  *v = g.array().floor().cast<int>().matrix();
  return true;
}

/// Not thread safe: make one per thread (cheap).
class Lookup {
 public:
  explicit Lookup(const EsdfMap& map) : map_(map) {}

  /// nullptr when the block is not allocated.
  const EsdfBlock* block(const BlockIndex& b) {
    if (has_cached_ && b == cached_index_) return cached_;
    const auto it = map_.blocks.find(b);
    cached_ = it == map_.blocks.end() ? nullptr : &it->second;
    cached_index_ = b;
    has_cached_ = true;
    return cached_;
  }

  /// Status of voxel v; its distance in *distance_m when known.
  EsdfStatus read(const GlobalVoxelIndex& v, float* distance_m) {
    const BlockIndex b = blockOfVoxel(v);
    const EsdfBlock* blk = block(b);
    if (blk == nullptr) return EsdfStatus::kOutside;
    const Eigen::Vector3i l = v - b * kBlockEdge;
    const EsdfVoxel& voxel = (*blk)[linearVoxelIndex(l.x(), l.y(), l.z())];
    if (!esdfObserved(voxel)) return EsdfStatus::kUnknown;
    *distance_m = voxel.distance_m;
    return EsdfStatus::kKnown;
  }

 private:
  const EsdfMap& map_;
  const EsdfBlock* cached_ = nullptr;
  BlockIndex cached_index_ = BlockIndex::Zero();
  bool has_cached_ = false;
};

/// What a ball scan looks for among the voxel centres within the radius.
enum class ScanTarget {
  kUnknown,   // unobserved or unallocated voxels
  kObstacle,  // observed site or inside voxels (distance below half a voxel)
};

/// True when some voxel centre within radius_m of c is a `target` voxel.
bool ballContains(Lookup& lookup, float voxel_size_m, const Eigen::Vector3f& c, float radius_m,
                  ScanTarget target);

}  // namespace strata::esdf_query_detail
