#pragma once
// The JSON report and the series of `strata-bench soak` (soak_command.h).
#include <string>

#include "json.h"
#include "soak_plateau.h"
#include "soak_run.h"

namespace strata::bench {

/// The samples as the plateau computation takes them.
SoakSeries soakSeries(const SoakRun& run);

/// {"totals": ..., "memory": ..., "plateau": ..., "session_ends_s": [...], "samples": columns}.
Json soakResults(const SoakRun& run, const PlateauVerdict& verdict);

/// One paragraph: throughput, drops, memory at start / warm-up end / end, the verdict.
std::string describeSoak(const SoakRun& run, const PlateauVerdict& verdict);

}  // namespace strata::bench
