#pragma once
// DiscoveredObject (change detection) -> change_event_t.
#include <cstdint>

#include "strata/change/object_discovery.h"
#include "strata/change_event_t.hpp"

namespace strata::lcm_io {

change_event_t encodeChangeEvent(const change::DiscoveredObject& object, int num_objects,
                                 std::int64_t utime);

}  // namespace strata::lcm_io
