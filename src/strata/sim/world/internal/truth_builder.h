#pragma once
// Session ground truth from the generated layouts (internal to World).
#include <vector>

#include "strata/sim/world/internal/layout.h"
#include "strata/sim/world/session_truth.h"

namespace strata::sim {

/// One SessionTruth per layout: poses, presence, change labels, and the session's light (the
/// file's light in session 0, varied per later session when the file asks for it).
std::vector<SessionTruth> makeSessionTruths(const WorldSpec& spec,
                                            const std::vector<ObjectSpec>& objects,
                                            const std::vector<Layout>& layouts);

}  // namespace strata::sim
