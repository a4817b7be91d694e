#pragma once
// Object database models -> object_update_t (one message per model a session created or
// extended). The model's mesh travels in its model frame; each instance carries T_W_M.
#include <cstdint>

#include "strata/objects/object_model.h"
#include "strata/object_update_t.hpp"

namespace strata::lcm_io {

/// `index` counts 1..`count` over the updates of one session's end.
object_update_t encodeObjectUpdate(const objects::ObjectModel& model, int session, bool new_model,
                                   int index, int count, std::int64_t utime);

}  // namespace strata::lcm_io
