#include "strata/explore/history_graph.h"

#include <algorithm>
#include <functional>
#include <limits>
#include <queue>

namespace strata::explore {

int HistoryGraph::addNode(const Eigen::Vector3f& position_W) {
  positions_.push_back(position_W);
  edges_.emplace_back();
  return static_cast<int>(positions_.size()) - 1;
}

bool HistoryGraph::hasEdge(int a, int b) const {
  return std::any_of(edges_[a].begin(), edges_[a].end(), [b](const Edge& e) { return e.to == b; });
}

void HistoryGraph::addEdge(int a, int b) {
  if (a == b || hasEdge(a, b)) return;
  const double length = (positions_[a] - positions_[b]).norm();
  edges_[a].push_back({b, length});
  edges_[b].push_back({a, length});
}

void HistoryGraph::removeEdge(int a, int b) {
  auto drop = [](std::vector<Edge>& list, int to) {
    list.erase(std::remove_if(list.begin(), list.end(), [to](const Edge& e) { return e.to == to; }),
               list.end());
  };
  drop(edges_[a], b);
  drop(edges_[b], a);
}

std::size_t HistoryGraph::edgeCount() const {
  std::size_t count = 0;
  for (const auto& list : edges_) count += list.size();
  return count / 2;
}

std::vector<int> HistoryGraph::near(const Eigen::Vector3f& p_W, float radius_m,
                                    std::size_t max_count) const {
  std::vector<std::pair<float, int>> found;
  for (std::size_t i = 0; i < positions_.size(); ++i) {
    const float d = (positions_[i] - p_W).norm();
    if (d <= radius_m) found.emplace_back(d, static_cast<int>(i));
  }
  std::sort(found.begin(), found.end());
  std::vector<int> out;
  for (std::size_t i = 0; i < found.size() && i < max_count; ++i) out.push_back(found[i].second);
  return out;
}

std::vector<double> HistoryGraph::shortestFrom(int source, std::vector<int>& parents) const {
  std::vector<double> distance(positions_.size(), std::numeric_limits<double>::infinity());
  parents.assign(positions_.size(), -1);
  using Item = std::pair<double, int>;
  std::priority_queue<Item, std::vector<Item>, std::greater<Item>> queue;
  distance[source] = 0.0;
  queue.emplace(0.0, source);
  while (!queue.empty()) {
    const auto [d, node] = queue.top();
    queue.pop();
    if (d > distance[node]) continue;
    for (const Edge& e : edges_[node]) {
      if (d + e.length_m < distance[e.to]) {
        distance[e.to] = d + e.length_m;
        parents[e.to] = node;
        queue.emplace(distance[e.to], e.to);
      }
    }
  }
  return distance;
}

std::vector<int> HistoryGraph::pathTo(const std::vector<int>& parents, int source, int target) {
  std::vector<int> path;
  for (int n = target; n >= 0; n = parents[n]) {
    path.push_back(n);
    if (n == source) break;
  }
  if (path.empty() || path.back() != source) return {};
  return {path.rbegin(), path.rend()};
}

}  // namespace strata::explore
