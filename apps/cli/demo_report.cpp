#include "cli/demo_report.h"

#include <sstream>

#include "cli/report_json.h"
#include "strata/core/atomic_file.h"

namespace strata::apps {
namespace {

std::string idList(const std::vector<int>& ids) {
  std::ostringstream out;
  out << "[";
  for (std::size_t i = 0; i < ids.size(); ++i) out << (i ? ", " : "") << ids[i];
  out << "]";
  return out.str();
}

/// Adds the counts' members (precision, recall, moved objects, ...) to `j`.
void addCounts(const change::ObjectCounts& c, Json& j) {
  j["precision"] = c.precision();
  j["recall"] = c.recall();
  j["moved_objects"] = c.moved;
  j["found"] = c.found;
  j["segments"] = c.segments;
  j["false_positives"] = c.false_positives;
  j["over_segmented"] = c.over_segmented;
  j["under_segmented"] = c.under_segmented;
}

Json matchesJson(const change::SessionObjectEvaluation& e) {
  Json matches = Json::array();
  for (const change::ObjectMatch& m : e.objects) {
    Json j;
    j["id"] = m.object_id;
    j["name"] = m.name;
    j["seen_m2"] = jsonFloat(m.visible_area_m2);
    j["evaluated"] = m.evaluated;
    j["found"] = m.found;
    j["segment"] = m.best_segment;
    j["coverage"] = m.coverage;
    j["on_object"] = m.on_object;
    j["segments"] = m.segments;
    matches.push_back(std::move(j));
  }
  return matches;
}

Json vioJson(const VioSessionResult& v) {
  Json j;
  j["stereo_frames"] = v.stereo_frames;
  j["tracked"] = v.tracked;
  j["failures"] = v.failures;
  j["first_tracking_s"] = v.first_tracking_s;
  j["rgbd_frames"] = v.rgbd_frames;
  j["fused"] = v.fused();
  j["skipped_before_tracking"] = v.skipped_before_tracking;
  j["skipped_in_gaps"] = v.skipped_in_gaps;
  j["skipped_after_tracking"] = v.skipped_after_tracking;
  j["ate_rmse_m"] = v.ate_rmse_m;
  j["ate_max_m"] = v.ate_max_m;
  j["rotation_rmse_deg"] = v.rotation_rmse_deg;
  j["render_s"] = v.render_s;
  j["vio_s"] = v.vio_s;
  return j;
}

Json demoSessionJson(const SessionResult& r, const change::SessionObjectEvaluation& e) {
  const double n = r.frames > 0 ? static_cast<double>(r.frames) : 1.0;
  Json j;
  j["session"] = r.session;
  j["frames"] = r.frames;
  j["recorded_frames"] = r.recorded_frames;
  j["render_fps"] = r.render_s > 0 ? r.frames / r.render_s : 0.0;
  j["fuse_wall_ms_per_frame"] = r.fuse_wall_ms / n;
  j["fuse_device_ms_per_frame"] = r.fuse_device_ms / n;
  j["blocks"] = r.blocks;
  j["tsdf_mean_abs_error_m"] = r.tsdf.mean_abs_error_m;
  j["tsdf_voxels_compared"] = r.tsdf.voxels;
  j["mesh_vertices"] = r.mesh_vertices;
  j["mesh_mean_distance_m"] = r.mesh.mean_distance_m;
  j["mesh_p99_distance_m"] = r.mesh.p99_distance_m;
  j["mesh_fraction_within_voxel"] = r.mesh.fraction_within;
  j["changed_object_ids"] = r.changed_ids;
  j["discovered_objects"] = r.objects;
  if (r.vio) j["vio"] = vioJson(*r.vio);
  addCounts(e.counts, j);
  j["moved_objects_matched"] = matchesJson(e);
  return j;
}

Json evaluationJson(const change::WorldEvaluation& e) {
  const change::StaticMapEvaluation& s = e.static_map;
  Json j;
  addCounts(e.totals, j);
  j["static_seen_points"] = s.seen_points;
  j["static_completeness"] = s.completeness;
  j["static_mesh_area_m2"] = s.mesh_area_m2;
  j["static_ghost_area_m2"] = s.ghost_area_m2;
  j["static_ghost_share"] = s.ghostShare();
  return j;
}

std::string summarizeVio(const DemoReport& report) {
  std::ostringstream s;
  s.precision(3);
  s << "Poses from stereo VIO (anchored at the truth where tracking starts), fused poses against "
       "the truth (RMSE, max):";
  std::size_t frames = 0, before = 0, gaps = 0, after = 0, failures = 0;
  for (const SessionResult& r : report.sessions) {
    const VioSessionResult& v = *r.vio;
    s << (r.session > 0 ? "," : "") << " session " << r.session << " " << 1000.0 * v.ate_rmse_m
      << " / " << 1000.0 * v.ate_max_m << " mm";
    frames += v.rgbd_frames;
    before += v.skipped_before_tracking;
    gaps += v.skipped_in_gaps;
    after += v.skipped_after_tracking;
    failures += v.failures;
  }
  s << "; " << before + gaps + after << " of " << frames << " RGB-D frames not fused (" << before
    << " before tracking, " << gaps << " in tracking gaps, " << after << " after it), " << failures
    << " tracking failures.";
  return s.str();
}

}  // namespace

void writeDemoReport(const DemoReport& report, const DiffResult& result, const DiffFiles& files,
                     const DiffRunInfo& info, const std::string& path) {
  Json sessions = Json::array();
  for (std::size_t i = 0; i < report.sessions.size(); ++i) {
    sessions.push_back(demoSessionJson(report.sessions[i], report.evaluation.sessions.at(i)));
  }
  Json j;
  j["world"] = report.world;
  j["seed"] = report.seed;
  j["map"] = report.map_config;
  j["device"] = report.device;
  j["total_s"] = report.total_s;
  j["sessions"] = std::move(sessions);
  j["evaluation"] = evaluationJson(report.evaluation);
  if (!report.incremental_json.empty()) j["incremental"] = parseJson(report.incremental_json);
  if (report.alignment) j["alignment"] = parseJson(demoAlignJson(*report.alignment));
  if (report.localization)
    j["localization"] = parseJson(demoLocalizeJson(*report.localization));
  if (!report.objects_json.empty()) j["objects"] = parseJson(report.objects_json);
  j["change_detection"] = parseJson(diffReportJson(result, files, info));
  writeTextAtomically(path, jsonFileText(j));
}

std::string summarizeDemo(const DemoReport& report, const std::string& out_dir) {
  std::size_t frames = 0, recorded = 0;
  double render_s = 0.0, fuse_ms = 0.0, tsdf_error = 0.0, within = 0.0;
  for (const SessionResult& r : report.sessions) {
    frames += r.frames;
    recorded += r.recorded_frames;
    render_s += r.render_s;
    fuse_ms += r.fuse_wall_ms;
    tsdf_error += r.tsdf.mean_abs_error_m;
    within += r.mesh.fraction_within;
  }
  const double sessions = report.sessions.empty() ? 1.0 : double(report.sessions.size());
  std::ostringstream s;
  s.precision(3);
  s << "Simulated and fused " << report.sessions.size() << " sessions of world '" << report.world
    << "' (seed " << report.seed << "), " << frames << " frames (of " << recorded
    << " recorded at 30 Hz), in " << report.total_s
    << " s on " << report.device << " (" << report.map_config << "): rendering "
    << (render_s > 0 ? frames / render_s : 0.0) << " frames/s, fusion "
    << (frames > 0 ? fuse_ms / frames : 0.0) << " ms/frame. Against the ground truth: mean "
    << "|TSDF - SDF| " << 1000.0 * tsdf_error / sessions << " mm near surfaces, "
    << 100.0 * within / sessions << " % of mesh vertices within one voxel of the true surface. ";
  for (const SessionResult& r : report.sessions) {
    if (r.session > 0) {
      s << "Session " << r.session << " changed objects " << idList(r.changed_ids) << ". ";
    }
  }
  const change::StaticMapEvaluation& st = report.evaluation.static_map;
  s << "Change detection over all sessions: " << change::describeCounts(report.evaluation.totals)
    << "; static map: " << 100.0 * st.completeness
    << " % of the static surface seen within 2 cm of the static mesh, " << 100.0 * st.ghostShare()
    << " % of its area on moved objects. Wrote the static mesh, per-session meshes (fused and "
    << "true), views, label overlays, object meshes and report.json to " << out_dir << "/.";
  if (!report.incremental_summary.empty()) s << " " << report.incremental_summary;
  if (!report.sessions.empty() && report.sessions.front().vio) s << " " << summarizeVio(report);
  if (report.alignment) s << " " << summarizeDemoAlign(*report.alignment);
  if (report.localization) s << " " << summarizeDemoLocalize(*report.localization);
  if (!report.objects_summary.empty()) s << " " << report.objects_summary;
  return s.str();
}

}  // namespace strata::apps
