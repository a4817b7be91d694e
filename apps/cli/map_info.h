#pragma once
// The text of `strata map info`: a table for people, JSON for scripts.
#include <string>
#include <vector>

#include "strata/store/store_types.h"

namespace strata::apps {

/// One row per session (id, name, aligned, keyframes, edges by kind, resources, path, span), a
/// total line, then the resource problems when `verified`.
std::string mapInfoTable(const std::string& db_path,
                         const std::vector<store::SessionSummary>& sessions,
                         const std::vector<store::ResourceProblem>& problems, bool verified);
/// {"database", "schema_version", "sessions": [...], "resource_problems": [...] (when verified)}.
std::string mapInfoJson(const std::string& db_path,
                        const std::vector<store::SessionSummary>& sessions,
                        const std::vector<store::ResourceProblem>& problems, bool verified);

}  // namespace strata::apps
