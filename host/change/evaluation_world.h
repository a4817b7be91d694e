#pragma once
// Change detection of a whole simulated world scored against its ground truth: every session's
// discovered objects (evaluateObjects) and the static map (evaluateStaticMap).
#include <vector>

#include "change/evaluation.h"
#include "change/evaluation_truth.h"
#include "change/evaluation_visibility.h"
#include "sim/world/world.h"

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

}  // namespace strata::change
