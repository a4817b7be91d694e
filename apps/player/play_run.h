#pragma once
// strata-play's work: replay a dataset over LCM at real time or as fast as the mapper fuses, then
// end the mapper's session and optionally have it save its map.
#include <lcm/lcm-cpp.hpp>

#include "player/play_options.h"

namespace strata::apps {

/// Returns the process exit code; errors print a message naming the problem.
int runPlay(const PlayOptions& options);
/// The same on `lcm` instead of options.url (tests: memq://, where publisher and subscribers
/// share one LCM object).
int runPlay(const PlayOptions& options, lcm::LCM& lcm);

}  // namespace strata::apps
