#pragma once
// What a change-detection run found, as JSON (report.json) and as a closing paragraph.
#include <string>

#include "cli/diff_outputs.h"
#include "strata/mapper/session_diff.h"

namespace strata::apps {

struct DiffRunInfo {
  std::string device;
  std::string map_config;  // MapConfig::describe()
  change::ChangeConfig change;
  change::ObjectConfig objects;
  double total_s = 0.0;
};

/// A JSON object of "change_config", "object_config", "static_mesh" and "sessions" (with every
/// object's id, size, bounds, centroid and file): the members report.json holds beside its
/// command, device, map and times.
std::string diffReportJson(const DiffResult& result, const DiffFiles& files,
                           const DiffRunInfo& info);

/// report.json of `strata diff`, written atomically.
void writeDiffReport(const std::string& path, const DiffResult& result, const DiffFiles& files,
                     const DiffRunInfo& info);

/// One paragraph: sessions, frames, time, device, objects per session, files written.
std::string summarizeDiff(const DiffResult& result, const DiffRunInfo& info,
                          const std::string& out_dir);

}  // namespace strata::apps
