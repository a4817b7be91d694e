#pragma once
// Change detection of a whole simulated world scored against its ground truth: every session's
// discovered objects (evaluateObjects) and the static map (evaluateStaticMap).
#include <vector>

#include "strata/change/eval/evaluation.h"
#include "strata/change/eval/evaluation_truth.h"
#include "strata/change/eval/evaluation_visibility.h"
#include "strata/sim/world/world.h"

namespace strata::change {

struct WorldEvaluation {
  std::vector<SessionObjectEvaluation> sessions;
  ObjectCounts totals;  // over all sessions
  StaticMapEvaluation static_map;
};

/// `objects[i]` and `seen[i]`: session i's discovered objects and what it saw. Moved objects are
/// judged against all sessions (ChangeDetector recomputes every session's dynamic part against
/// the final static map). Throws InputError when the counts disagree with the world's sessions.
WorldEvaluation evaluateWorld(const sim::World& world,
                              const std::vector<std::vector<DiscoveredObject>>& objects,
                              const Mesh& static_mesh,
                              const std::vector<const VisibleSurface*>& seen,
                              const EvaluationConfig& config);

/// Recall over arrivals: a moved object counts in session s >= 1 only where it changed since
/// session s - 1 (moved there or added): the instance in which its change is new. Its instances in
/// sessions where it stood as in the session before are left out: a map that fuses only the images
/// that show something new looks at an object again only when it changed.
struct ArrivalCounts {
  std::size_t arrivals = 0;  // evaluated moved objects that changed since the previous session
  std::size_t found = 0;
  double recall() const { return arrivals ? double(found) / double(arrivals) : 1.0; }
};
/// Whether object `object_id` changed in `session` since the session before (false in session 0).
bool isArrival(const sim::World& world, int session, int object_id);
/// Throws InputError when `evaluation` has more sessions than `world`.
ArrivalCounts arrivalCounts(const sim::World& world, const WorldEvaluation& evaluation);

}  // namespace strata::change
