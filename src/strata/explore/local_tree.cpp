#include "strata/explore/local_tree.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "strata/core/error.h"

namespace strata::explore {
namespace {

using Candidate = TreeCandidate;

Eigen::Vector3f sampleBox(const Eigen::AlignedBox3f& box, std::mt19937_64& rng) {
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  const Eigen::Vector3f t(u(rng), u(rng), u(rng));
  return box.min() + t.cwiseProduct(box.sizes());
}

/// A sample pulled towards its nearest node to at most max_edge; nullopt-like parent -1 when it
/// lands too close to that node.
Candidate steer(const Eigen::Vector3f& sample_W, int parent, const Eigen::Vector3f& from_W,
                const LocalTreeConfig& config) {
  Eigen::Vector3f delta = sample_W - from_W;
  const float length = delta.norm();
  if (length < config.min_edge_m) return {sample_W, -1};
  if (length > config.max_edge_m) delta *= config.max_edge_m / length;
  return {from_W + delta, parent};
}

/// Moves candidates that lie near an obstacle up the ESDF gradient (one checker call).
void pushFromObstacles(std::vector<Candidate>& candidates, plan::CollisionChecker& checker,
                       float radius_m, const LocalTreeConfig& config) {
  if (config.push_clearance_m <= 0.0f || candidates.empty()) return;
  std::vector<Eigen::Vector3f> points;
  for (const Candidate& c : candidates) points.push_back(c.position_W);
  const std::vector<EsdfSample> samples = checker.sample(points);
  const float want = radius_m + config.push_clearance_m;
  for (std::size_t i = 0; i < candidates.size(); ++i) {
    const EsdfSample& s = samples[i];
    if (s.status != EsdfStatus::kKnown || s.distance_m >= want) continue;
    const float g = s.gradient.norm();
    if (!(g > 1e-3f)) continue;
    const float step = std::min(config.push_max_m, want - s.distance_m);
    candidates[i].position_W += s.gradient * (step / g);
  }
}

}  // namespace

void LocalTreeConfig::validate() const {
  if (nodes < 1) throw InputError("local tree nodes must be >= 1");
  if (!(max_edge_m > 0.0f) || !(min_edge_m >= 0.0f) || min_edge_m >= max_edge_m) {
    throw InputError("local tree edges: need 0 <= min_edge_m < max_edge_m");
  }
  if (!(half_extent_m.minCoeff() > 0.0f) || !half_extent_m.allFinite()) {
    throw InputError("local tree half_extent_m must be positive");
  }
  if (!(push_clearance_m >= 0.0f) || !(push_max_m >= 0.0f)) {
    throw InputError("local tree push_clearance_m and push_max_m must be >= 0");
  }
  if (batch < 1 || max_batches < 1) throw InputError("local tree batch and max_batches >= 1");
  if (!(lambda_per_m >= 0.0f) || !std::isfinite(lambda_per_m)) {
    throw InputError("local tree lambda_per_m must be >= 0");
  }
  if (!(full_height_share >= 0.0f && full_height_share <= 1.0f)) {
    throw InputError("local tree full_height_share must be in [0, 1]");
  }
}

Eigen::AlignedBox3f localBox(const Eigen::Vector3f& centre_W, const Eigen::Vector3f& half_extent_m,
                             const Eigen::AlignedBox3f& bounds_W) {
  const Eigen::AlignedBox3f box(centre_W - half_extent_m, centre_W + half_extent_m);
  return box.intersection(bounds_W);
}

Eigen::AlignedBox3f fullHeightBox(const Eigen::Vector3f& centre_W,
                                  const Eigen::Vector3f& half_extent_m,
                                  const Eigen::AlignedBox3f& bounds_W) {
  Eigen::AlignedBox3f box = localBox(centre_W, half_extent_m, bounds_W);
  if (box.isEmpty()) return box;
  box.min().z() = bounds_W.min().z();
  box.max().z() = bounds_W.max().z();
  return box;
}

LocalTree::LocalTree(const Eigen::Vector3f& root_W) {
  TreeNode root;
  root.position_W = root_W;
  nodes_.push_back(root);
}

EsdfSegment LocalTree::checkedPart(const Candidate& c, float radius_m) const {
  const Eigen::Vector3f from = nodes_[c.parent].position_W;
  if (c.parent != 0) return {from, c.position_W};
  // NOTE: edges from the root are checked from one radius out: the robot is already in the
  // root's sphere, and a surface observed there since (noise, a newly seen corner) must not
  // keep it from moving away from it.
  const Eigen::Vector3f delta = c.position_W - from;
  const float length = delta.norm();
  const float skip = std::min(radius_m, 0.5f * length);
  return {from + delta * (skip / std::max(length, 1e-6f)), c.position_W};
}

int LocalTree::nearest(const Eigen::Vector3f& p_W) const {
  int best = 0;
  float best_d2 = std::numeric_limits<float>::max();
  for (std::size_t i = 0; i < nodes_.size(); ++i) {
    const float d2 = (nodes_[i].position_W - p_W).squaredNorm();
    if (d2 < best_d2) {
      best_d2 = d2;
      best = static_cast<int>(i);
    }
  }
  return best;
}

void LocalTree::seedBranch(const std::vector<Eigen::Vector3f>& chain_W,
                           plan::CollisionChecker& checker, float radius_m) {
  if (chain_W.empty()) return;
  std::vector<EsdfSegment> segments;
  Eigen::Vector3f from = nodes_[0].position_W;
  for (const Eigen::Vector3f& p : chain_W) {
    segments.push_back({from, p});
    from = p;
  }
  const std::vector<std::uint8_t> free =
      checker.segmentsFree(segments, radius_m, UnknownPolicy::kOccupied);
  int parent = 0;
  for (std::size_t i = 0; i < chain_W.size() && free[i]; ++i) {
    TreeNode node;
    node.position_W = chain_W[i];
    node.parent = parent;
    node.cost_m = nodes_[parent].cost_m + (chain_W[i] - nodes_[parent].position_W).norm();
    nodes_.push_back(node);
    parent = static_cast<int>(nodes_.size()) - 1;
  }
}

void LocalTree::grow(int target_nodes, const Eigen::AlignedBox3f& box_W,
                     const LocalTreeConfig& config, plan::CollisionChecker& checker, float radius_m,
                     std::mt19937_64& rng) {
  grow(target_nodes, box_W, box_W, config, checker, radius_m, rng);
}

void LocalTree::grow(int target_nodes, const Eigen::AlignedBox3f& box_W,
                     const Eigen::AlignedBox3f& tall_box_W, const LocalTreeConfig& config,
                     plan::CollisionChecker& checker, float radius_m, std::mt19937_64& rng) {
  if (box_W.isEmpty()) return;
  std::uniform_real_distribution<float> which(0.0f, 1.0f);
  for (int call = 0; call < config.max_batches; ++call) {
    if (static_cast<int>(nodes_.size()) - 1 >= target_nodes) return;
    std::vector<Candidate> candidates;
    std::vector<EsdfSegment> segments;
    for (int i = 0; i < config.batch; ++i) {
      const bool tall = config.full_height_share > 0.0f && !tall_box_W.isEmpty() &&
                        which(rng) < config.full_height_share;
      const Eigen::Vector3f sample = sampleBox(tall ? tall_box_W : box_W, rng);
      const int parent = nearest(sample);
      const Candidate c = steer(sample, parent, nodes_[parent].position_W, config);
      if (c.parent < 0) continue;
      candidates.push_back(c);
    }
    pushFromObstacles(candidates, checker, radius_m, config);
    for (const Candidate& c : candidates) segments.push_back(checkedPart(c, radius_m));
    if (segments.empty()) continue;
    const std::vector<std::uint8_t> free =
        checker.segmentsFree(segments, radius_m, UnknownPolicy::kOccupied);
    for (std::size_t i = 0; i < candidates.size(); ++i) {
      if (!free[i] || static_cast<int>(nodes_.size()) - 1 >= target_nodes) continue;
      const Candidate& c = candidates[i];
      // Candidates of one batch did not see each other: keep them apart here.
      if ((nodes_[nearest(c.position_W)].position_W - c.position_W).norm() < config.min_edge_m) {
        continue;
      }
      TreeNode node;
      node.position_W = c.position_W;
      node.parent = c.parent;
      node.cost_m = nodes_[c.parent].cost_m + (c.position_W - nodes_[c.parent].position_W).norm();
      nodes_.push_back(node);
    }
  }
}

void LocalTree::score(float lambda_per_m) {
  for (TreeNode& node : nodes_) {
    const float own = node.gain_m3 * std::exp(-lambda_per_m * node.cost_m);
    node.score_m3 = node.parent < 0 ? 0.0f : nodes_[node.parent].score_m3 + own;
  }
}

int LocalTree::best() const {
  int best = 0;
  for (std::size_t i = 1; i < nodes_.size(); ++i) {
    if (best == 0 || nodes_[i].score_m3 > nodes_[best].score_m3) best = static_cast<int>(i);
  }
  return best;
}

std::vector<int> LocalTree::branch(int node) const {
  std::vector<int> out;
  for (int n = node; n > 0; n = nodes_[n].parent) out.push_back(n);
  return {out.rbegin(), out.rend()};
}

}  // namespace strata::explore
