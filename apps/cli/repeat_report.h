#pragma once
// The outputs of `strata repeat` (repeat_command.h): report.json, the per-step trajectory CSV.
#include <string>
#include <vector>

#include "cli/report_json.h"
#include "strata/repeat/repeat_loop.h"

namespace strata::apps {

/// One run's figures (following error, drift, localisations, stops, collisions).
Json repeatRunJson(const std::string& mode, const repeat::RepeatResult& r);
/// t, true x y z, estimate x y z, following error: one line per motion step, atomically.
void writeRepeatCsv(const std::string& path, const repeat::RepeatResult& r);

}  // namespace strata::apps
