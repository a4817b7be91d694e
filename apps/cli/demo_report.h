#pragma once
// What the multi-session demo measured, as JSON and as a closing paragraph.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "cli/demo_align.h"
#include "cli/demo_localize.h"
#include "cli/demo_vio.h"
#include "cli/diff_report.h"
#include "cli/select_incremental.h"
#include "strata/mapper/eval/accuracy.h"
#include "strata/change/eval/evaluation_world.h"
#include "strata/objects/eval/object_db_eval.h"

namespace strata::apps {

struct SessionResult {
  int session = 0;
  std::size_t frames = 0;
  std::size_t recorded_frames = 0;  // of the full recording at 30 Hz (frames are spread over it)
  double render_s = 0.0;
  double fuse_wall_ms = 0.0;    // summed over frames
  double fuse_device_ms = 0.0;  // summed over frames
  std::size_t blocks = 0;
  std::size_t mesh_vertices = 0;
  eval::TsdfAccuracy tsdf;
  eval::MeshAccuracy mesh;
  std::vector<int> changed_ids;  // objects changed since the previous session
  std::size_t objects = 0;       // discovered
  std::optional<VioSessionResult> vio;  // --vio: the odometry the session was fused on
};

struct DemoReport {
  std::string world;
  std::uint64_t seed = 0;
  std::string map_config;
  std::string device;
  std::vector<SessionResult> sessions;
  change::WorldEvaluation evaluation;  // discovered objects and static map against the truth
  double total_s = 0.0;
  std::string incremental_summary;               // `--incremental`, "" without
  std::string incremental_json;                  // the same as a JSON object, "" without
  std::optional<IncrementalResult> incremental;  // the figures behind both
  std::optional<DemoAlignResult> alignment;      // `--align`
  std::optional<DemoLocalizeResult> localization;  // `--localize`
  /// The object database built over the sessions as the last step (cli/demo_objects.h).
  std::string objects_summary;                      // one sentence, "" when not built
  std::string objects_json;                         // report.json's "objects", "" when not built
  std::optional<eval::ObjectDbEvaluation> objects;  // its score against the world's truth
};

/// Writes the report as JSON, atomically: the demo's figures, the evaluation and the change
/// detection's own members (diffReportJson) under "change_detection".
void writeDemoReport(const DemoReport& report, const DiffResult& result, const DiffFiles& files,
                     const DiffRunInfo& info, const std::string& path);
/// One paragraph for the terminal.
std::string summarizeDemo(const DemoReport& report, const std::string& out_dir);

}  // namespace strata::apps
