#pragma once
// What a change-detection run found, as JSON (report.json) and as a closing paragraph.
#include <ostream>
#include <string>

#include "cli/diff_outputs.h"
#include "cli/diff_pipeline.h"

namespace strata::apps {

struct DiffRunInfo {
  std::string device;
  std::string map_config;  // MapConfig::describe()
  change::ChangeConfig change;
  change::ObjectConfig objects;
  double total_s = 0.0;
};

/// Writes the JSON members (no braces) "change_config", "object_config", "static_mesh" and
/// "sessions" (with every object's id, size, bounds, centroid and file), each line indented by
/// `indent` spaces.
void writeDiffJsonMembers(std::ostream& out, const DiffResult& result, const DiffFiles& files,
                          const DiffRunInfo& info, int indent);

/// report.json of `strata diff`, written atomically.
void writeDiffReport(const std::string& path, const DiffResult& result, const DiffFiles& files,
                     const DiffRunInfo& info);

/// One paragraph: sessions, frames, time, device, objects per session, files written.
std::string summarizeDiff(const DiffResult& result, const DiffRunInfo& info,
                          const std::string& out_dir);

/// "a\"b" for a JSON string.
std::string jsonString(const std::string& text);

}  // namespace strata::apps
