// Grid A* on the traversable voxel centres (contract in grid_astar.h).
#include "strata/plan/grid_astar.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <queue>

#include "strata/plan/internal/path_prune.h"
#include "strata/core/clock.h"

namespace strata::plan {
namespace {

using Clock = SteadyClock;

/// One of the 26 moves: its offset, its length in voxels, and the offsets (relative to the cell
/// moved from) that must be traversable for it: the other corners of the unit cube it crosses.
struct Move {
  Eigen::Vector3i step;
  float length_voxels;
  std::vector<Eigen::Vector3i> corners;
};

std::vector<Move> makeMoves() {
  std::vector<Move> moves;
  for (int dz = -1; dz <= 1; ++dz) {
    for (int dy = -1; dy <= 1; ++dy) {
      for (int dx = -1; dx <= 1; ++dx) {
        const Eigen::Vector3i step(dx, dy, dz);
        const int nonzero = (dx != 0) + (dy != 0) + (dz != 0);
        if (nonzero == 0) continue;
        Move m{step, std::sqrt(static_cast<float>(nonzero)), {}};
        // Every partial move: each proper, non-empty subset of the step's non-zero components.
        for (int mask = 1; mask < 7; ++mask) {
          const Eigen::Vector3i part((mask & 1) ? dx : 0, (mask & 2) ? dy : 0, (mask & 4) ? dz : 0);
          if (part != Eigen::Vector3i::Zero() && part != step &&
              std::find(m.corners.begin(), m.corners.end(), part) == m.corners.end()) {
            m.corners.push_back(part);
          }
        }
        moves.push_back(m);
      }
    }
  }
  return moves;
}

/// 3D octile distance in voxels.
float octile(const Eigen::Vector3i& a, const Eigen::Vector3i& b) {
  std::array<int, 3> d{std::abs(a.x() - b.x()), std::abs(a.y() - b.y()), std::abs(a.z() - b.z())};
  std::sort(d.begin(), d.end());  // d[0] <= d[1] <= d[2]
  constexpr float kSqrt2 = 1.41421356f, kSqrt3 = 1.73205081f;
  return (kSqrt3 - kSqrt2) * d[0] + (kSqrt2 - 1.0f) * d[1] + static_cast<float>(d[2]);
}

struct OpenEntry {
  float f;
  float h;
  std::int64_t cell;
  bool operator>(const OpenEntry& o) const { return f > o.f || (f == o.f && h > o.h); }
};

}  // namespace

/// Per-cell search state, reused between queries: a generation stamp marks what is current.
struct GridAStarPlanner::Scratch {
  std::vector<float> g;
  std::vector<std::int64_t> parent;
  std::vector<std::uint32_t> seen;    // == generation: g and parent are this query's
  std::vector<std::uint32_t> closed;  // == generation: expanded in this query
  std::uint32_t generation = 0;

  void reset(std::size_t cells) {
    if (g.size() != cells) {
      g.assign(cells, 0.0f);
      parent.assign(cells, -1);
      seen.assign(cells, 0);
      closed.assign(cells, 0);
      generation = 0;
    }
    ++generation;
  }
  std::size_t bytes() const {
    return g.capacity() * sizeof(float) + parent.capacity() * sizeof(std::int64_t) +
           (seen.capacity() + closed.capacity()) * sizeof(std::uint32_t);
  }
};

namespace {

/// A* from `start` to `goal` (cell indices); the cells of the path, start first, or empty.
std::vector<std::int64_t> searchGrid(const TraversabilityGrid& grid, std::int64_t start,
                                     std::int64_t goal, GridAStarPlanner::Scratch& s,
                                     std::uint64_t* expanded);

}  // namespace

GridAStarPlanner::GridAStarPlanner(const EsdfMap& esdf, CollisionChecker& checker)
    : esdf_(esdf), checker_(checker), scratch_(std::make_unique<Scratch>()) {}

GridAStarPlanner::~GridAStarPlanner() = default;

const TraversabilityGrid& GridAStarPlanner::prepare(float radius_m, UnknownPolicy unknown) {
  for (const auto& grid : grids_) {
    if (grid->radiusM() == radius_m && grid->unknown() == unknown) return *grid;
  }
  const auto start = Clock::now();
  grids_.push_back(
      std::make_unique<TraversabilityGrid>(checker_, allocatedBounds(esdf_), radius_m, unknown));
  stats_.build_ms = msSince(start);
  stats_.cells = grids_.back()->cellCount();
  stats_.traversable = grids_.back()->traversableCount();
  return *grids_.back();
}

std::size_t GridAStarPlanner::memoryBytes() const {
  std::size_t bytes = scratch_->bytes();
  for (const auto& grid : grids_) bytes += grid->memoryBytes();
  return bytes;
}

std::string describePoint(const char* what, const Eigen::Vector3f& p_W) {
  char text[128];
  std::snprintf(text, sizeof(text), "%s (%.2f, %.2f, %.2f)", what, static_cast<double>(p_W.x()),
                static_cast<double>(p_W.y()), static_cast<double>(p_W.z()));
  return text;
}

std::string endpointProblem(const TraversabilityGrid& grid, const char* what,
                            const Eigen::Vector3f& p_W, float voxel_size_m) {
  if (!p_W.allFinite()) return std::string(what) + " is not a finite point";
  const Eigen::Vector3i v = (p_W / voxel_size_m).array().floor().cast<int>();
  if (grid.index(v) < 0) return describePoint(what, p_W) + " is outside the map";
  if (!grid.traversable(v)) {
    char text[160];
    std::snprintf(text, sizeof(text), " is in collision (robot radius %.2f m, unknown space %s)",
                  static_cast<double>(grid.radiusM()),
                  grid.unknown() == UnknownPolicy::kOccupied ? "occupied" : "free");
    return describePoint(what, p_W) + text;
  }
  return "";
}

PlanResult GridAStarPlanner::plan(const PlanRequest& request) {
  PlanResult result;
  if (!std::isfinite(request.radius_m) || request.radius_m < 0.0f) {
    result.message = "robot radius must be finite and >= 0";
    return result;
  }
  const TraversabilityGrid& grid = prepare(request.radius_m, request.unknown);
  const std::uint64_t checks_before = checker_.spheresTested();
  const auto start_time = Clock::now();
  const float voxel_m = checker_.voxelSize();
  result.message = endpointProblem(grid, "start", request.start_W, voxel_m);
  if (result.message.empty())
    result.message = endpointProblem(grid, "goal", request.goal_W, voxel_m);
  if (!result.message.empty()) return result;
  const auto cellOf = [&](const Eigen::Vector3f& p) {
    return grid.index((p / voxel_m).array().floor().cast<int>());
  };
  const std::vector<std::int64_t> cells = searchGrid(
      grid, cellOf(request.start_W), cellOf(request.goal_W), *scratch_, &stats_.expanded);
  if (cells.empty()) {
    result.message = "no path: start and goal are not connected through free space";
    result.planning_ms = msSince(start_time);
    return result;
  }
  std::vector<Eigen::Vector3f> raw{request.start_W};
  for (std::int64_t c : cells) raw.push_back(voxelCenter(grid.voxel(c), voxel_m));
  raw.push_back(request.goal_W);
  raw.erase(std::unique(raw.begin(), raw.end()), raw.end());
  result.path_W = relaxPath(prunePath(raw, checker_, request.radius_m, request.unknown), checker_,
                            request.radius_m, request.unknown);
  result.planning_ms = msSince(start_time);
  result.collision_checks = checker_.spheresTested() - checks_before;
  result.success = true;
  result.length_m = pathLength(result.path_W);
  result.min_clearance_m = checker_.minClearance(result.path_W);
  return result;
}

namespace {

std::vector<std::int64_t> searchGrid(const TraversabilityGrid& grid, std::int64_t start,
                                     std::int64_t goal, GridAStarPlanner::Scratch& s,
                                     std::uint64_t* expanded) {
  static const std::vector<Move> kMoves = makeMoves();
  s.reset(grid.cellCount());
  const std::uint32_t gen = s.generation;
  const Eigen::Vector3i goal_v = grid.voxel(goal);
  std::priority_queue<OpenEntry, std::vector<OpenEntry>, std::greater<OpenEntry>> open;
  s.g[start] = 0.0f;
  s.parent[start] = -1;
  s.seen[start] = gen;
  open.push({octile(grid.voxel(start), goal_v), 0.0f, start});
  *expanded = 0;
  while (!open.empty()) {
    const OpenEntry top = open.top();
    open.pop();
    if (s.closed[top.cell] == gen) continue;
    s.closed[top.cell] = gen;
    ++*expanded;
    if (top.cell == goal) break;
    const Eigen::Vector3i v = grid.voxel(top.cell);
    for (const Move& m : kMoves) {
      const std::int64_t n = grid.index(v + m.step);
      if (n < 0 || !grid.traversable(n) || s.closed[n] == gen) continue;
      const float g = s.g[top.cell] + m.length_voxels;
      if (s.seen[n] == gen && s.g[n] <= g) continue;
      const bool corners_free =
          std::all_of(m.corners.begin(), m.corners.end(),
                      [&](const Eigen::Vector3i& c) { return grid.traversable(v + c); });
      if (!corners_free) continue;
      s.g[n] = g;
      s.parent[n] = top.cell;
      s.seen[n] = gen;
      const float h = octile(v + m.step, goal_v);
      open.push({g + h, h, n});
    }
  }
  if (s.closed[goal] != gen) return {};
  std::vector<std::int64_t> cells;
  for (std::int64_t c = goal; c >= 0; c = s.parent[c]) cells.push_back(c);
  std::reverse(cells.begin(), cells.end());
  return cells;
}

}  // namespace

}  // namespace strata::plan
