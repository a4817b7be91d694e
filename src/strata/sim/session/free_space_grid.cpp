#include "strata/sim/session/internal/free_space_grid.h"

#include <cmath>
#include <deque>
#include <limits>
#include <queue>

namespace strata::sim {

FreeSpaceGrid::FreeSpaceGrid(const WorldScene& scene, const Eigen::AlignedBox2d& bounds,
                             double height_m, double clearance_m, double cell_m)
    : origin_(bounds.min()), cell_m_(cell_m) {
  width_ = std::max(1, static_cast<int>(std::ceil(bounds.sizes().x() / cell_m)));
  height_ = std::max(1, static_cast<int>(std::ceil(bounds.sizes().y() / cell_m)));
  free_.assign(static_cast<std::size_t>(width_) * height_, 0);
  for (int y = 0; y < height_; ++y) {
    for (int x = 0; x < width_; ++x) {
      const Eigen::Vector2d c = centreOf(index(x, y));
      const Eigen::Vector3f p(static_cast<float>(c.x()), static_cast<float>(c.y()),
                              static_cast<float>(height_m));
      free_[index(x, y)] = scene.signedDistance(p) >= clearance_m ? 1 : 0;
    }
  }
}

Eigen::Vector2i FreeSpaceGrid::cellOf(const Eigen::Vector2d& p) const {
  const Eigen::Vector2d g = (p - origin_) / cell_m_;
  return Eigen::Vector2i(std::clamp(static_cast<int>(std::floor(g.x())), 0, width_ - 1),
                         std::clamp(static_cast<int>(std::floor(g.y())), 0, height_ - 1));
}

Eigen::Vector2d FreeSpaceGrid::centreOf(int cell) const {
  return origin_ + cell_m_ * Eigen::Vector2d(cell % width_ + 0.5, cell / width_ + 0.5);
}

bool FreeSpaceGrid::nearestFree(const Eigen::Vector2d& p, Eigen::Vector2d* free_p) const {
  const Eigen::Vector2i start = cellOf(p);
  std::vector<char> seen(free_.size(), 0);
  std::deque<int> queue{index(start.x(), start.y())};
  seen[queue.front()] = 1;
  while (!queue.empty()) {
    const int cell = queue.front();
    queue.pop_front();
    if (free_[cell]) {
      *free_p = centreOf(cell);
      return true;
    }
    const int x = cell % width_, y = cell / width_;
    for (const auto& [dx, dy] : {std::pair{1, 0}, {-1, 0}, {0, 1}, {0, -1}}) {
      const int nx = x + dx, ny = y + dy;
      if (nx < 0 || ny < 0 || nx >= width_ || ny >= height_ || seen[index(nx, ny)]) continue;
      seen[index(nx, ny)] = 1;
      queue.push_back(index(nx, ny));
    }
  }
  return false;
}

std::vector<Eigen::Vector2d> FreeSpaceGrid::path(const Eigen::Vector2d& a,
                                                 const Eigen::Vector2d& b) const {
  Eigen::Vector2d a_free, b_free;
  if (!nearestFree(a, &a_free) || !nearestFree(b, &b_free)) return {};
  const Eigen::Vector2i start = cellOf(a_free), goal = cellOf(b_free);
  const int goal_cell = index(goal.x(), goal.y());
  std::vector<double> cost(free_.size(), std::numeric_limits<double>::infinity());
  std::vector<int> parent(free_.size(), -1);
  using Item = std::pair<double, int>;  // (cost + heuristic, cell)
  std::priority_queue<Item, std::vector<Item>, std::greater<Item>> open;
  const int start_cell = index(start.x(), start.y());
  cost[start_cell] = 0.0;
  open.push({0.0, start_cell});
  while (!open.empty()) {
    const int cell = open.top().second;
    open.pop();
    if (cell == goal_cell) break;
    const int x = cell % width_, y = cell / width_;
    for (int dy = -1; dy <= 1; ++dy) {
      for (int dx = -1; dx <= 1; ++dx) {
        const int nx = x + dx, ny = y + dy;
        if ((dx == 0 && dy == 0) || nx < 0 || ny < 0 || nx >= width_ || ny >= height_) continue;
        const int next = index(nx, ny);
        if (!free_[next]) continue;
        const double step = (dx != 0 && dy != 0) ? std::sqrt(2.0) : 1.0;
        if (cost[cell] + step >= cost[next]) continue;
        cost[next] = cost[cell] + step;
        parent[next] = cell;
        open.push({cost[next] + Eigen::Vector2d(nx - goal.x(), ny - goal.y()).norm(), next});
      }
    }
  }
  if (!std::isfinite(cost[goal_cell])) return {};
  std::vector<Eigen::Vector2d> cells;
  for (int cell = goal_cell; cell != -1; cell = parent[cell]) cells.push_back(centreOf(cell));
  return std::vector<Eigen::Vector2d>(cells.rbegin(), cells.rend());
}

}  // namespace strata::sim
