#pragma once
// The history graph of the history-aware planner: positions the robot visited or saw as good
// views, joined by segments that were known free when they were added (an RRT edge, a flown
// step, a checked shortcut). Shortest paths by Dijkstra. Small (one node per step or cached
// view), so plain adjacency lists and linear nearest-neighbour scans.
// Frames: world, metres. Thread safety: not thread safe.
#include <Eigen/Core>
#include <vector>

namespace strata::explore {

class HistoryGraph {
 public:
  int addNode(const Eigen::Vector3f& position_W);
  /// Undirected edge weighted by its length; a repeated edge is kept once.
  void addEdge(int a, int b);
  void removeEdge(int a, int b);
  bool hasEdge(int a, int b) const;

  /// Nodes within radius_m of p, nearest first, at most max_count.
  std::vector<int> near(const Eigen::Vector3f& p_W, float radius_m, std::size_t max_count) const;

  /// Path lengths from `source` to every node (infinity when not connected); parents for
  /// pathTo (-1 for the source and unreached nodes).
  std::vector<double> shortestFrom(int source, std::vector<int>& parents) const;
  /// Nodes source..target (empty when target was not reached).
  static std::vector<int> pathTo(const std::vector<int>& parents, int source, int target);

  const Eigen::Vector3f& position(int node) const { return positions_[node]; }
  std::size_t size() const { return positions_.size(); }
  std::size_t edgeCount() const;

 private:
  struct Edge {
    int to;
    double length_m;
  };
  std::vector<Eigen::Vector3f> positions_;
  std::vector<std::vector<Edge>> edges_;
};

}  // namespace strata::explore
