#include "strata/change/eval/evaluation_world.h"

#include <algorithm>
#include <string>

#include "strata/core/error.h"

namespace strata::change {

WorldEvaluation evaluateWorld(const sim::World& world,
                              const std::vector<std::vector<DiscoveredObject>>& objects,
                              const Mesh& static_mesh,
                              const std::vector<const VisibleSurface*>& seen,
                              const EvaluationConfig& config) {
  const auto sessions = static_cast<std::size_t>(world.sessionCount());
  if (objects.size() != sessions || seen.size() != sessions) {
    throw InputError("evaluateWorld: " + std::to_string(objects.size()) + " object lists and " +
                     std::to_string(seen.size()) + " visibility records for a world of " +
                     std::to_string(sessions) + " sessions");
  }
  WorldEvaluation result;
  for (std::size_t s = 0; s < sessions; ++s) {
    const int session = static_cast<int>(s);
    const std::vector<int> moved = movedObjectIds(world, session, MovedReference::kAllSessions);
    result.sessions.push_back(evaluateObjects(
        session, sessionTruthObjects(world, session, moved, *seen[s], config.min_views), objects[s],
        config));
    result.totals += result.sessions.back().counts;
  }
  result.static_map =
      evaluateStaticMap(static_mesh, staticTruthMesh(world), movedTruthMeshes(world),
                        seenStaticPoints(world, seen, config.min_views), config);
  return result;
}

bool isArrival(const sim::World& world, int session, int object_id) {
  if (session == 0) return false;                                        // nothing came before it
  const std::vector<int> changed = world.session(session).changedIds();  // ascending
  return std::binary_search(changed.begin(), changed.end(), object_id);
}

ArrivalCounts arrivalCounts(const sim::World& world, const WorldEvaluation& evaluation) {
  if (evaluation.sessions.size() > static_cast<std::size_t>(world.sessionCount())) {
    throw InputError("arrivalCounts: an evaluation of " +
                     std::to_string(evaluation.sessions.size()) + " sessions for a world of " +
                     std::to_string(world.sessionCount()));
  }
  ArrivalCounts counts;
  for (const SessionObjectEvaluation& session : evaluation.sessions) {
    for (const ObjectMatch& object : session.objects) {
      if (!object.evaluated || !isArrival(world, session.session, object.object_id)) continue;
      ++counts.arrivals;
      counts.found += object.found ? 1 : 0;
    }
  }
  return counts;
}

}  // namespace strata::change
