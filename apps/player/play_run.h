#pragma once
// strata-play's work: replay a dataset over LCM at real time or as fast as the mapper fuses, then
// end the mapper's session and optionally have it save its map.
#include "player/play_options.h"

namespace strata::apps {

/// Returns the process exit code; errors print a message naming the problem.
int runPlay(const PlayOptions& options);

}  // namespace strata::apps
