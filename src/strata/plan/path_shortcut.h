#pragma once
// Path shortening with batched capsule checks: the polyline is densified, every pair of its
// vertices is tested for a free straight segment in ONE batch (one device dispatch per round),
// and the shortest path of that visibility graph (a DAG along the path, dynamic programming)
// replaces the polyline; a few rounds re-densify the result. Deterministic (no sampling).
// NOTE: chosen over OMPL's PathSimplifier, which asks one motion at a time (one dispatch each)
// and draws random shortcuts; here all candidates of a round share one batch.
// Guarantee: the result is the input or a polyline whose every segment passed
// CollisionChecker::segmentsFree (so pathFree accepts it), from the same start to the same goal,
// never longer.
// Thread safety: not thread safe (uses the checker).
#include <Eigen/Core>
#include <vector>

#include "strata/plan/collision_checker.h"

namespace strata::plan {

struct ShortcutOptions {
  /// Rounds of densify + visibility DP; a round that gains nothing ends early.
  int rounds = 3;
  /// Vertices of the densified polyline per round (pairs tested ~ n^2 / 2): resolution of the
  /// shortcuts against the size of the batch.
  int max_vertices = 40;
};

struct ShortcutStats {
  int rounds = 0;            // rounds run
  std::size_t segments = 0;  // candidate segments tested
  int batches = 0;           // calls to the checker (one per round, one for the merged result)
};

/// `path_W` should be free (e.g. a planner's path); radius and policy as in PlanRequest.
std::vector<Eigen::Vector3f> shortcutPath(const std::vector<Eigen::Vector3f>& path_W,
                                          CollisionChecker& checker, float radius_m,
                                          UnknownPolicy unknown,
                                          const ShortcutOptions& options = {},
                                          ShortcutStats* stats = nullptr);

}  // namespace strata::plan
