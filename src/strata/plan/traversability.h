#pragma once
// Where a spherical robot may stand: one flag per voxel centre of a dense box of the ESDF's voxel
// grid (the bounding box of the allocated blocks). A centre is traversable when the robot sphere
// there is free under the policy (esdf_query.h: no obstacle voxel centre, and under kOccupied no
// unknown one, within the radius). Grid A* searches it; the topological map groups it into boxes.
// Also 6-connected components, which are the connectivity of both planners (grid A* allows a
// diagonal move only where the axis-aligned moves around it are traversable too).
// Thread safety: immutable after construction; const methods are thread safe.
#include <Eigen/Core>
#include <cstdint>
#include <vector>

#include "strata/esdf/esdf_query.h"
#include "strata/plan/collision_checker.h"

namespace strata::plan {

/// A box of global voxel indices, both corners inclusive.
struct VoxelBox {
  Eigen::Vector3i lo = Eigen::Vector3i::Zero();
  Eigen::Vector3i hi = Eigen::Vector3i::Constant(-1);
  bool empty() const { return (hi.array() < lo.array()).any(); }
  bool contains(const Eigen::Vector3i& v) const {
    return (v.array() >= lo.array()).all() && (v.array() <= hi.array()).all();
  }
  std::int64_t volume() const;
};

/// The global voxel box covered by the allocated blocks of `esdf` (empty when it has none).
VoxelBox allocatedBounds(const EsdfMap& esdf);

class TraversabilityGrid {
 public:
  /// Sphere tests of every voxel centre of `bounds` through `checker` (in batches), for a robot of
  /// `radius_m` under `unknown`. InputError for a negative or non-finite radius.
  TraversabilityGrid(CollisionChecker& checker, const VoxelBox& bounds, float radius_m,
                     UnknownPolicy unknown);

  const VoxelBox& bounds() const { return bounds_; }
  const Eigen::Vector3i& dims() const { return dims_; }
  std::size_t cellCount() const { return free_.size(); }
  float radiusM() const { return radius_m_; }
  UnknownPolicy unknown() const { return unknown_; }

  /// Linear index of a voxel inside bounds() (x fastest); -1 outside.
  std::int64_t index(const Eigen::Vector3i& v) const;
  Eigen::Vector3i voxel(std::int64_t index) const;
  bool traversable(std::int64_t index) const { return free_[static_cast<std::size_t>(index)] != 0; }
  bool traversable(const Eigen::Vector3i& v) const;
  std::size_t traversableCount() const;
  std::size_t memoryBytes() const { return free_.capacity(); }

  /// 6-connected components of the traversable cells: one label per cell (-1: not traversable),
  /// labels 0..n-1.
  std::vector<std::int32_t> components(std::int32_t* count = nullptr) const;

 private:
  VoxelBox bounds_;
  Eigen::Vector3i dims_ = Eigen::Vector3i::Zero();
  float radius_m_ = 0.0f;
  UnknownPolicy unknown_ = UnknownPolicy::kOccupied;
  std::vector<std::uint8_t> free_;
};

/// Sphere tests of every voxel centre of `box` (x fastest), in batches through `checker`.
std::vector<std::uint8_t> sphereFreeInBox(CollisionChecker& checker, const VoxelBox& box,
                                          float radius_m, UnknownPolicy unknown);

}  // namespace strata::plan
