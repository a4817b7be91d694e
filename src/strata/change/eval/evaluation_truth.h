#pragma once
// Ground truth of a simulated world for evaluation.h: which objects changed, their true surfaces
// per session, the static truth, and what the sessions saw of it.
#include <vector>

#include "strata/change/eval/evaluation.h"
#include "strata/change/eval/evaluation_visibility.h"
#include "strata/sim/world/world.h"

namespace strata::change {

/// Which sessions an object's place in `session` is compared with to call it moved.
enum class MovedReference {
  kAllSessions,      // any other session (the static map after all sessions)
  kEarlierSessions,  // sessions before it (the static map as it stood when it was added)
};

/// Objects present in `session` that are absent, or at another pose, in a reference session.
std::vector<int> movedObjectIds(const sim::World& world, int session, MovedReference reference);

/// Objects whose presence or pose differs between some two sessions.
std::vector<int> changingObjectIds(const sim::World& world);

/// An object's true surface at its pose in a session, world frame.
Mesh objectMeshInSession(const sim::World& world, int object_id, int session);

/// Every object present in the session, `moved` set for the ids listed, with what `seen` saw in
/// at least `min_views` frames.
std::vector<TruthObject> sessionTruthObjects(const sim::World& world, int session,
                                             const std::vector<int>& moved_ids,
                                             const VisibleSurface& seen, int min_views);

/// The static world plus every object that never changed.
Mesh staticTruthMesh(const sim::World& world);

/// Every pose of every object that changed, one mesh each.
std::vector<Mesh> movedTruthMeshes(const sim::World& world);

/// Static surface (structure and never-changing objects) that one of the sessions saw in at least
/// `min_views` frames, deduplicated.
std::vector<Eigen::Vector3f> seenStaticPoints(const sim::World& world,
                                              const std::vector<const VisibleSurface*>& seen,
                                              int min_views);

}  // namespace strata::change
