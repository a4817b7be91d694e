#pragma once
// The before / after picture of an object database (docs/objects.md): for the models merged from
// the most observations, the largest single observation of each (its segment re-observed from its
// session's layer, as the database saw it) above the merged model, both raycast from the same
// viewpoint in the model frame. Shows what merging added: the sides no single session saw.
#include <vector>

#include "strata/mapper/session_diff.h"
#include "cli/objects_outputs.h"
#include "strata/core/types.h"
#include "strata/map/tsdf_map.h"

namespace strata::apps {

/// Up to `count` models merged from two observations or more, most merged first; `maps` as
/// buildObjectDatabase took them. A short notice when no model was merged.
ColorImage renderBeforeAfter(const ObjectsRun& run, const DiffResult& result,
                             const std::vector<TsdfMap>& maps, int count = 4, int size_px = 180);

}  // namespace strata::apps
