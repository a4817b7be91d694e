#include "strata/explore/reachable_space.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <deque>
#include <limits>
#include <sstream>
#include <thread>

#include "strata/core/error.h"

namespace strata::explore {
namespace {

constexpr int kTopCellVoxels = 16;  // edge of the cells handed to workers
constexpr double kMaxVoxels = double(1u << 31);

enum : std::uint8_t { kBlocked = 0, kFree = 1, kReached = 2 };

/// The free test of every voxel, cell by cell (see the header).
class FreeSpaceClassifier {
 public:
  FreeSpaceClassifier(const sim::WorldScene& scene, const ReachableSpace& grid,
                      std::vector<std::uint8_t>& state)
      : scene_(scene), grid_(grid), state_(state) {}

  void classify(const Eigen::Vector3i& lo, const Eigen::Vector3i& hi) {
    const Eigen::Vector3i n = hi - lo;
    const double h = grid_.voxel_size_m;
    const Eigen::Vector3d first = grid_.center(lo.x(), lo.y(), lo.z());
    const Eigen::Vector3d last = grid_.center(hi.x() - 1, hi.y() - 1, hi.z() - 1);
    const Eigen::Vector3d centre = 0.5 * (first + last);
    const double half_diagonal = 0.5 * (last - first).norm();
    const double d = scene_.distanceToSurface(centre);
    if (n == Eigen::Vector3i::Ones()) {
      set(lo, hi, d > 0.5 * h && !scene_.occupied(centre.cast<float>()));
      return;
    }
    if (d > half_diagonal + 0.5 * h) {
      // No surface within the cell's ball: every centre is on the same side, far enough.
      set(lo, hi, !scene_.occupied(centre.cast<float>()));
      return;
    }
    const Eigen::Vector3i mid = lo + (n.array() + 1).matrix() / 2;
    for (int octant = 0; octant < 8; ++octant) {
      Eigen::Vector3i a, b;
      for (int axis = 0; axis < 3; ++axis) {
        const bool upper = (octant >> axis) & 1;
        a[axis] = upper ? mid[axis] : lo[axis];
        b[axis] = upper ? hi[axis] : mid[axis];
      }
      if ((b - a).minCoeff() > 0) classify(a, b);
    }
  }

 private:
  void set(const Eigen::Vector3i& lo, const Eigen::Vector3i& hi, bool free) {
    const std::uint8_t value = free ? kFree : kBlocked;
    for (int z = lo.z(); z < hi.z(); ++z) {
      for (int y = lo.y(); y < hi.y(); ++y) {
        for (int x = lo.x(); x < hi.x(); ++x) state_[index(x, y, z)] = value;
      }
    }
  }
  std::size_t index(int x, int y, int z) const {
    return static_cast<std::size_t>(x) +
           static_cast<std::size_t>(grid_.dims.x()) *
               (static_cast<std::size_t>(y) + static_cast<std::size_t>(grid_.dims.y()) * z);
  }

  const sim::WorldScene& scene_;
  const ReachableSpace& grid_;
  std::vector<std::uint8_t>& state_;
};

void classifyAll(const sim::WorldScene& scene, const ReachableSpace& grid,
                 std::vector<std::uint8_t>& state) {
  const Eigen::Vector3i cells = (grid.dims.array() + kTopCellVoxels - 1) / kTopCellVoxels;
  const int cell_count = cells.prod();
  std::atomic<int> next{0};
  const auto work = [&] {
    FreeSpaceClassifier classifier(scene, grid, state);
    for (int c = next++; c < cell_count; c = next++) {
      const Eigen::Vector3i cell(c % cells.x(), (c / cells.x()) % cells.y(),
                                 c / (cells.x() * cells.y()));
      const Eigen::Vector3i lo = cell * kTopCellVoxels;
      const Eigen::Vector3i hi = (lo.array() + kTopCellVoxels).min(grid.dims.array());
      classifier.classify(lo, hi);
    }
  };
  // Cells write disjoint voxels of `state`.
  const int threads = std::max(1, std::min<int>(std::thread::hardware_concurrency(), cell_count));
  std::vector<std::thread> workers;
  for (int t = 1; t < threads; ++t) workers.emplace_back(work);
  work();
  for (std::thread& worker : workers) worker.join();
}

/// Marks every free voxel 6-connected to `start` kReached; returns how many.
std::size_t floodFill(const Eigen::Vector3i& dims, const Eigen::Vector3i& start,
                      std::vector<std::uint8_t>& state) {
  const auto index = [&](const Eigen::Vector3i& v) {
    return static_cast<std::size_t>(v.x()) +
           static_cast<std::size_t>(dims.x()) *
               (static_cast<std::size_t>(v.y()) + static_cast<std::size_t>(dims.y()) * v.z());
  };
  std::deque<Eigen::Vector3i> queue{start};
  state[index(start)] = kReached;
  std::size_t count = 1;
  while (!queue.empty()) {
    const Eigen::Vector3i v = queue.front();
    queue.pop_front();
    for (int axis = 0; axis < 3; ++axis) {
      for (int sign : {-1, 1}) {
        Eigen::Vector3i u = v;
        u[axis] += sign;
        if (u[axis] < 0 || u[axis] >= dims[axis] || state[index(u)] != kFree) continue;
        state[index(u)] = kReached;
        ++count;
        queue.push_back(u);
      }
    }
  }
  return count;
}

std::string describe(const Eigen::Vector3d& p) {
  std::ostringstream out;
  out << "(" << p.x() << ", " << p.y() << ", " << p.z() << ")";
  return out.str();
}

}  // namespace

ReachableSpace computeReachableSpace(const sim::WorldScene& scene,
                                     const Eigen::AlignedBox3d& bounds_W,
                                     const Eigen::Vector3d& start_W, double voxel_size_m) {
  if (!(voxel_size_m > 0.0) || !std::isfinite(voxel_size_m)) {
    throw InputError("computeReachableSpace: the voxel size must be positive");
  }
  if (bounds_W.isEmpty() || !bounds_W.sizes().allFinite()) {
    throw InputError("computeReachableSpace: the bounds are empty or not finite");
  }
  const Eigen::Vector3d cells = (bounds_W.sizes() / voxel_size_m).array().ceil();
  if (cells.prod() > kMaxVoxels) {
    throw InputError("computeReachableSpace: over 2^31 voxels; use larger voxels");
  }
  ReachableSpace space;
  space.origin_W = bounds_W.min();
  space.voxel_size_m = voxel_size_m;
  space.dims = cells.cast<int>().cwiseMax(1);
  if (!bounds_W.contains(start_W)) {
    throw InputError("computeReachableSpace: the start " + describe(start_W) +
                     " lies outside the bounds");
  }
  const Eigen::Vector3i start = ((start_W - space.origin_W) / voxel_size_m)
                                    .array()
                                    .floor()
                                    .cast<int>()
                                    .min(space.dims.array() - 1)
                                    .matrix();

  std::vector<std::uint8_t> state(static_cast<std::size_t>(space.dims.prod()), kBlocked);
  classifyAll(scene, space, state);
  space.free_count = static_cast<std::size_t>(std::count(state.begin(), state.end(), kFree));
  const std::size_t start_index = static_cast<std::size_t>(start.x()) +
                                  static_cast<std::size_t>(space.dims.x()) *
                                      (static_cast<std::size_t>(start.y()) +
                                       static_cast<std::size_t>(space.dims.y()) * start.z());
  if (state[start_index] != kFree) {
    throw InputError("computeReachableSpace: the start " + describe(start_W) +
                     " is not in free space (inside a solid or within half a voxel of a surface)");
  }
  space.reachable_count = floodFill(space.dims, start, state);
  space.reachable.resize(state.size());
  for (std::size_t i = 0; i < state.size(); ++i) space.reachable[i] = state[i] == kReached ? 1 : 0;
  space.volume_m3 = double(space.reachable_count) * std::pow(voxel_size_m, 3);
  return space;
}

double exploredFraction(const ReachableSpace& space, const TsdfMap& map, float min_weight) {
  if (space.reachable_count == 0) return 0.0;
  const double map_voxel_m = map.config().voxel_size_m;
  std::size_t observed = 0;
  for (int z = 0; z < space.dims.z(); ++z) {
    for (int y = 0; y < space.dims.y(); ++y) {
      for (int x = 0; x < space.dims.x(); ++x) {
        if (!space.isReachable(x, y, z)) continue;
        const GlobalVoxelIndex v =
            (space.center(x, y, z) / map_voxel_m).array().floor().cast<int>();
        const TsdfVoxel* voxel = map.findVoxel(v);
        if (voxel != nullptr && voxel->weight >= min_weight) ++observed;
      }
    }
  }
  return double(observed) / double(space.reachable_count);
}

double minClearanceAlong(const sim::WorldScene& scene,
                         const std::vector<Eigen::Vector3d>& positions_W) {
  double clearance = std::numeric_limits<double>::infinity();
  for (const Eigen::Vector3d& p : positions_W) {
    clearance = std::min(clearance, scene.distanceToSurface(p));
  }
  return clearance;
}

}  // namespace strata::explore
