#pragma once
// The local rapidly-exploring random tree both exploration planners grow at each step (Bircher
// et al. 2016, receding-horizon next-best-view): from the robot's position, through known free
// space only (capsule checks with UnknownPolicy::kOccupied, a batch of candidate edges per
// checker call; edges from the root from one radius out, so that the robot can always move away
// from a surface observed next to it), inside a box around the robot. Each node carries a view
// (position, yaw) and its gain; the score of a node is the gain accumulated along its branch, each
// view discounted by exp(-lambda * cost) with cost the branch length from the root (Eq. (1) of the
// NBVP paper). Frames: world, metres. Thread safety: not thread safe (the checker and the rng are
// shared).
#include <Eigen/Geometry>
#include <cstdint>
#include <random>
#include <vector>

#include "strata/plan/collision_checker.h"

namespace strata::explore {

struct LocalTreeConfig {
  /// Nodes (besides the root) a step grows: more sees farther, costs more gain evaluations.
  int nodes = 40;
  /// Longest edge; candidates farther from their nearest node are pulled in to this.
  float max_edge_m = 1.5f;
  /// Candidates closer than this to a node are dropped (they add no new view).
  float min_edge_m = 0.4f;
  /// The sampling box around the robot (half extents, metres), clipped to the bounds.
  Eigen::Vector3f half_extent_m = Eigen::Vector3f(4.0f, 4.0f, 0.6f);
  /// Candidate edges per checker call.
  int batch = 24;
  /// Checker calls per growth at most (a cluttered spot may never reach `nodes`).
  int max_batches = 10;
  /// Candidates closer than (check radius + this) to an obstacle are pushed up the ESDF gradient
  /// to that distance (at most push_max_m): edges through doors and gaps stay near their middle,
  /// where a capsule fits (metres; 0: off).
  float push_clearance_m = 0.15f;
  float push_max_m = 0.3f;
  /// Discount of a view's gain per metre of branch (1/m).
  float lambda_per_m = 0.5f;
  /// Share of the samples drawn over the whole height of the bounds (the box's x and y), the
  /// rest inside the box: views above and below the robot in a tall space, while the box keeps
  /// the tree dense around it. 0: the box only (NBVP's tree).
  float full_height_share = 0.0f;

  /// Throws InputError naming the bad field.
  void validate() const;
};

struct TreeNode {
  Eigen::Vector3f position_W = Eigen::Vector3f::Zero();
  int parent = -1;  // -1: the root
  float cost_m = 0.0f;
  float yaw_rad = 0.0f;
  float gain_m3 = 0.0f;   // of the node's own view
  float score_m3 = 0.0f;  // accumulated, discounted along the branch
};

/// A candidate node: its position and the node it would hang from.
struct TreeCandidate {
  Eigen::Vector3f position_W;
  int parent;
};

class LocalTree {
 public:
  explicit LocalTree(const Eigen::Vector3f& root_W);

  /// Adds the free prefix of a chain of positions below the root (re-seeding with the rest of
  /// the previous step's best branch). One checker call.
  void seedBranch(const std::vector<Eigen::Vector3f>& chain_W, plan::CollisionChecker& checker,
                  float radius_m);
  /// Grows until size() - 1 reaches target_nodes or max_batches checker calls were made.
  /// Samples fall in box_W, or with probability config.full_height_share in tall_box_W.
  void grow(int target_nodes, const Eigen::AlignedBox3f& box_W, const LocalTreeConfig& config,
            plan::CollisionChecker& checker, float radius_m, std::mt19937_64& rng);
  void grow(int target_nodes, const Eigen::AlignedBox3f& box_W,
            const Eigen::AlignedBox3f& tall_box_W, const LocalTreeConfig& config,
            plan::CollisionChecker& checker, float radius_m, std::mt19937_64& rng);

  /// score = parent's score + gain * exp(-lambda * cost), root first (parents precede children).
  void score(float lambda_per_m);
  /// The node of the highest score (0, the root, when there are no others).
  int best() const;
  /// Node indices from the root's child down to `node` (empty for the root).
  std::vector<int> branch(int node) const;

  std::vector<TreeNode>& nodes() { return nodes_; }
  const std::vector<TreeNode>& nodes() const { return nodes_; }
  std::size_t size() const { return nodes_.size(); }

 private:
  using Candidate = TreeCandidate;
  int nearest(const Eigen::Vector3f& p_W) const;
  /// The part of a candidate edge that is checked (local_tree.cpp: edges from the root).
  EsdfSegment checkedPart(const Candidate& c, float radius_m) const;

  std::vector<TreeNode> nodes_;
};

/// The box around `centre` clipped to `bounds` (empty when they do not overlap).
Eigen::AlignedBox3f localBox(const Eigen::Vector3f& centre_W, const Eigen::Vector3f& half_extent_m,
                             const Eigen::AlignedBox3f& bounds_W);
/// The same box in x and y, over the whole height of `bounds` in z.
Eigen::AlignedBox3f fullHeightBox(const Eigen::Vector3f& centre_W,
                                  const Eigen::Vector3f& half_extent_m,
                                  const Eigen::AlignedBox3f& bounds_W);

}  // namespace strata::explore
