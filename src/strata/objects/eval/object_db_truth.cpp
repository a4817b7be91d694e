// The truth of a simulated world for the object database's evaluation.
#include "strata/core/error.h"
#include "strata/change/eval/evaluation_truth.h"
#include "strata/objects/eval/object_db_eval.h"
#include "strata/sim/world/world.h"

namespace strata::eval {
namespace {

/// world_sessions, or 0..count-1 when empty; InputError for a session the world lacks.
std::vector<int> worldSessions(const sim::World& world, const std::vector<int>& world_sessions,
                               std::size_t count) {
  std::vector<int> sessions = world_sessions;
  if (sessions.empty()) {
    for (std::size_t i = 0; i < count; ++i) sessions.push_back(static_cast<int>(i));
  }
  for (int s : sessions) {
    if (s < 0 || s >= world.sessionCount()) {
      throw InputError("object database truth: session " + std::to_string(s) + " of world '" +
                       world.name() + "', which has " + std::to_string(world.sessionCount()));
    }
  }
  return sessions;
}

}  // namespace

ObjectDbTruth objectDbTruth(const sim::World& world, const std::vector<int>& world_sessions) {
  ObjectDbTruth truth;
  for (int id = 1; id <= world.objectCount(); ++id) {
    truth.shapes.push_back(world.object(id).shape);
    truth.names.push_back(world.object(id).name);
    truth.meshes_O.push_back(world.objectMesh(id));
  }
  const auto count = static_cast<std::size_t>(world.sessionCount());
  for (int s : worldSessions(world, world_sessions, count))
    truth.sessions.push_back(world.session(s));
  return truth;
}

std::vector<change::SessionObjectEvaluation> segmentIdentities(
    const sim::World& world, const std::vector<std::vector<change::DiscoveredObject>>& segments,
    const std::vector<int>& world_sessions, const change::EvaluationConfig& config) {
  const std::vector<int> sessions = worldSessions(world, world_sessions, segments.size());
  if (sessions.size() != segments.size()) {
    throw InputError("segmentIdentities: " + std::to_string(segments.size()) +
                     " sessions of segments for " + std::to_string(sessions.size()) +
                     " world sessions");
  }
  std::vector<change::SessionObjectEvaluation> result;
  for (std::size_t i = 0; i < segments.size(); ++i) {
    std::vector<int> present;
    for (const sim::ObjectState& o : world.session(sessions[i]).objects) {
      if (o.present) present.push_back(o.id);
    }
    std::vector<change::TruthObject> truth;
    for (int id : present) {
      change::TruthObject object;
      object.id = id;
      object.name = world.object(id).name;
      object.moved = true;  // every present object is a candidate identity
      object.mesh = change::objectMeshInSession(world, id, sessions[i]);
      truth.push_back(std::move(object));
    }
    result.push_back(change::evaluateObjects(static_cast<int>(i), truth, segments[i], config));
  }
  return result;
}

}  // namespace strata::eval
