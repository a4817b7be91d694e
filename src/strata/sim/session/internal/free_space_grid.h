#pragma once
// A 2D grid of where a hand-held camera may be: cells at camera height whose distance to every
// surface is at least the clearance. Paths between waypoints are planned on it (A*), so camera
// paths go through doors and around shelves and pillars instead of through them.
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <vector>

#include "strata/sim/world/world_scene.h"

namespace strata::sim {

class FreeSpaceGrid {
 public:
  FreeSpaceGrid(const WorldScene& scene, const Eigen::AlignedBox2d& bounds, double height_m,
                double clearance_m, double cell_m = 0.1);

  /// Nearest free cell centre to p (breadth-first over cells); false when nothing is free.
  bool nearestFree(const Eigen::Vector2d& p, Eigen::Vector2d* free_p) const;
  /// Shortest 8-connected path of free cell centres from a to b (both snapped to free cells),
  /// empty when they are not connected.
  std::vector<Eigen::Vector2d> path(const Eigen::Vector2d& a, const Eigen::Vector2d& b) const;

 private:
  int index(int x, int y) const { return y * width_ + x; }
  Eigen::Vector2i cellOf(const Eigen::Vector2d& p) const;
  Eigen::Vector2d centreOf(int cell) const;

  Eigen::Vector2d origin_;
  double cell_m_;
  int width_ = 0;
  int height_ = 0;
  std::vector<char> free_;
};

}  // namespace strata::sim
