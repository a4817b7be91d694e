// Traversability of voxel centres (contract in traversability.h).
#include "strata/plan/traversability.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "strata/core/error.h"

namespace strata::plan {
namespace {

// Centres per batch: large enough for the checker's threads (or one device dispatch), small
// enough that the centre list stays a few MB.
constexpr std::int64_t kBatchCentres = 1 << 16;

const Eigen::Vector3i kAxisSteps[6] = {{1, 0, 0},  {-1, 0, 0}, {0, 1, 0},
                                       {0, -1, 0}, {0, 0, 1},  {0, 0, -1}};

}  // namespace

std::int64_t VoxelBox::volume() const {
  if (empty()) return 0;
  const Eigen::Vector3i d = hi - lo + Eigen::Vector3i::Ones();
  return static_cast<std::int64_t>(d.x()) * d.y() * d.z();
}

VoxelBox allocatedBounds(const EsdfMap& esdf) {
  VoxelBox box;
  if (esdf.blocks.empty()) return box;
  Eigen::Vector3i lo = Eigen::Vector3i::Constant(std::numeric_limits<int>::max());
  Eigen::Vector3i hi = Eigen::Vector3i::Constant(std::numeric_limits<int>::min());
  for (const auto& [b, block] : esdf.blocks) {
    lo = lo.cwiseMin(b);
    hi = hi.cwiseMax(b);
  }
  box.lo = lo * kBlockEdge;
  box.hi = hi * kBlockEdge + Eigen::Vector3i::Constant(kBlockEdge - 1);
  return box;
}

std::vector<std::uint8_t> sphereFreeInBox(CollisionChecker& checker, const VoxelBox& box,
                                          float radius_m, UnknownPolicy unknown) {
  const std::int64_t cells = box.volume();
  std::vector<std::uint8_t> out(static_cast<std::size_t>(cells), 0);
  const Eigen::Vector3i d = box.hi - box.lo + Eigen::Vector3i::Ones();
  const float voxel_m = checker.voxelSize();
  std::vector<Eigen::Vector3f> centres;
  for (std::int64_t begin = 0; begin < cells; begin += kBatchCentres) {
    const std::int64_t end = std::min(cells, begin + kBatchCentres);
    centres.clear();
    for (std::int64_t i = begin; i < end; ++i) {
      const Eigen::Vector3i v(static_cast<int>(i % d.x()), static_cast<int>(i / d.x() % d.y()),
                              static_cast<int>(i / (static_cast<std::int64_t>(d.x()) * d.y())));
      centres.push_back(voxelCenter(box.lo + v, voxel_m));
    }
    const std::vector<std::uint8_t> free = checker.spheresFree(centres, radius_m, unknown);
    std::copy(free.begin(), free.end(), out.begin() + begin);
  }
  return out;
}

TraversabilityGrid::TraversabilityGrid(CollisionChecker& checker, const VoxelBox& bounds,
                                       float radius_m, UnknownPolicy unknown)
    : bounds_(bounds), radius_m_(radius_m), unknown_(unknown) {
  if (!std::isfinite(radius_m) || radius_m < 0.0f) {
    throw InputError("robot radius must be finite and >= 0 (got " + std::to_string(radius_m) +
                     " m)");
  }
  dims_ = bounds.empty() ? Eigen::Vector3i::Zero()
                         : Eigen::Vector3i(bounds.hi - bounds.lo + Eigen::Vector3i::Ones());
  free_ = sphereFreeInBox(checker, bounds, radius_m, unknown);
}

std::int64_t TraversabilityGrid::index(const Eigen::Vector3i& v) const {
  if (!bounds_.contains(v)) return -1;
  const Eigen::Vector3i l = v - bounds_.lo;
  return l.x() + static_cast<std::int64_t>(dims_.x()) *
                     (l.y() + static_cast<std::int64_t>(dims_.y()) * l.z());
}

Eigen::Vector3i TraversabilityGrid::voxel(std::int64_t index) const {
  const std::int64_t plane = static_cast<std::int64_t>(dims_.x()) * dims_.y();
  return bounds_.lo + Eigen::Vector3i(static_cast<int>(index % dims_.x()),
                                      static_cast<int>(index / dims_.x() % dims_.y()),
                                      static_cast<int>(index / plane));
}

bool TraversabilityGrid::traversable(const Eigen::Vector3i& v) const {
  const std::int64_t i = index(v);
  return i >= 0 && traversable(i);
}

std::size_t TraversabilityGrid::traversableCount() const {
  return static_cast<std::size_t>(std::count(free_.begin(), free_.end(), std::uint8_t{1}));
}

std::vector<std::int32_t> TraversabilityGrid::components(std::int32_t* count) const {
  std::vector<std::int32_t> label(free_.size(), -1);
  std::int32_t next = 0;
  std::vector<std::int64_t> stack;
  for (std::size_t seed = 0; seed < free_.size(); ++seed) {
    if (free_[seed] == 0 || label[seed] >= 0) continue;
    label[seed] = next;
    stack.assign(1, static_cast<std::int64_t>(seed));
    while (!stack.empty()) {
      const Eigen::Vector3i v = voxel(stack.back());
      stack.pop_back();
      for (const Eigen::Vector3i& step : kAxisSteps) {
        const std::int64_t n = index(v + step);
        if (n < 0 || free_[static_cast<std::size_t>(n)] == 0) continue;
        if (label[static_cast<std::size_t>(n)] >= 0) continue;
        label[static_cast<std::size_t>(n)] = next;
        stack.push_back(n);
      }
    }
    ++next;
  }
  if (count != nullptr) *count = next;
  return label;
}

}  // namespace strata::plan
