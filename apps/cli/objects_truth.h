#pragma once
// Simulator truth for the object database: found beside session folders written by `strata sim`
// (<dir>/session_K with <dir>/ground_truth/session_K/objects.json naming the world and seed), or
// given (the demo's world); the database scored against it (eval/object_db_eval.h).
#include <memory>
#include <string>
#include <vector>

#include "cli/objects_outputs.h"
#include "strata/objects/eval/object_db_eval.h"
#include "strata/sim/world/world.h"

namespace strata::apps {

struct SimTruth {
  std::shared_ptr<const sim::World> world;
  std::vector<int> world_sessions;  // the world's session of each input session
};

/// The truth of `session_dirs` when every one is a `strata sim` session folder with its ground
/// truth beside it and the world it names loads (a shipped name, or `world_path` when given);
/// else nullptr, with the reason in `why_not`. A world that loads but disagrees with a session's
/// objects.json (another seed or file) is an InputError naming the folder.
std::shared_ptr<const SimTruth> findSimTruth(const std::vector<std::string>& session_dirs,
                                             const std::string& world_path, std::string& why_not);

/// Segment identities, truth and the database's evaluation in one call.
eval::ObjectDbEvaluation evaluateObjectsRun(const SimTruth& truth, const DiffResult& result,
                                            const ObjectsRun& run);

}  // namespace strata::apps
