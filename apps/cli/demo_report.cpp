#include "cli/demo_report.h"

#include <sstream>

#include "core/atomic_file.h"
#include "core/json_text.h"

namespace strata::apps {
namespace {

std::string idList(const std::vector<int>& ids) {
  std::ostringstream out;
  out << "[";
  for (std::size_t i = 0; i < ids.size(); ++i) out << (i ? ", " : "") << ids[i];
  out << "]";
  return out.str();
}

void writeCounts(std::ostringstream& out, const change::ObjectCounts& c) {
  out << "\"precision\": " << c.precision() << ", \"recall\": " << c.recall()
      << ", \"moved_objects\": " << c.moved << ", \"found\": " << c.found
      << ", \"segments\": " << c.segments << ", \"false_positives\": " << c.false_positives
      << ", \"over_segmented\": " << c.over_segmented
      << ", \"under_segmented\": " << c.under_segmented;
}

void writeMatches(std::ostringstream& out, const change::SessionObjectEvaluation& e) {
  out << "[";
  for (std::size_t i = 0; i < e.objects.size(); ++i) {
    const change::ObjectMatch& m = e.objects[i];
    out << (i ? ", " : "") << "{\"id\": " << m.object_id << ", \"name\": " << jsonString(m.name)
        << ", \"seen_m2\": " << m.visible_area_m2 << ", \"evaluated\": " << m.evaluated
        << ", \"found\": " << m.found << ", \"segment\": " << m.best_segment
        << ", \"coverage\": " << m.coverage << ", \"on_object\": " << m.on_object
        << ", \"segments\": " << m.segments << "}";
  }
  out << "]";
}

void writeVio(std::ostringstream& out, const VioSessionResult& v) {
  out << "{\"stereo_frames\": " << v.stereo_frames << ", \"tracked\": " << v.tracked
      << ", \"failures\": " << v.failures
      << ", \"first_tracking_s\": " << jsonNumber(v.first_tracking_s)
      << ", \"rgbd_frames\": " << v.rgbd_frames << ", \"fused\": " << v.fused()
      << ", \"skipped_before_tracking\": " << v.skipped_before_tracking
      << ", \"skipped_in_gaps\": " << v.skipped_in_gaps
      << ", \"skipped_after_tracking\": " << v.skipped_after_tracking
      << ", \"ate_rmse_m\": " << jsonNumber(v.ate_rmse_m)
      << ", \"ate_max_m\": " << jsonNumber(v.ate_max_m)
      << ", \"rotation_rmse_deg\": " << jsonNumber(v.rotation_rmse_deg)
      << ", \"render_s\": " << v.render_s << ", \"vio_s\": " << v.vio_s << "}";
}

void writeSession(std::ostringstream& out, const SessionResult& r,
                  const change::SessionObjectEvaluation& e) {
  const double n = r.frames > 0 ? static_cast<double>(r.frames) : 1.0;
  out << "    {\"session\": " << r.session << ", \"frames\": " << r.frames
      << ", \"recorded_frames\": " << r.recorded_frames
      << ", \"render_fps\": " << (r.render_s > 0 ? r.frames / r.render_s : 0.0)
      << ", \"fuse_wall_ms_per_frame\": " << r.fuse_wall_ms / n
      << ", \"fuse_device_ms_per_frame\": " << r.fuse_device_ms / n << ", \"blocks\": " << r.blocks
      << ", \"tsdf_mean_abs_error_m\": " << r.tsdf.mean_abs_error_m
      << ", \"tsdf_voxels_compared\": " << r.tsdf.voxels
      << ", \"mesh_vertices\": " << r.mesh_vertices
      << ", \"mesh_mean_distance_m\": " << r.mesh.mean_distance_m
      << ", \"mesh_p99_distance_m\": " << r.mesh.p99_distance_m
      << ", \"mesh_fraction_within_voxel\": " << r.mesh.fraction_within
      << ", \"changed_object_ids\": " << idList(r.changed_ids)
      << ", \"discovered_objects\": " << r.objects << ",\n     ";
  if (r.vio) {
    out << "\"vio\": ";
    writeVio(out, *r.vio);
    out << ",\n     ";
  }
  writeCounts(out, e.counts);
  out << ",\n     \"moved_objects_matched\": ";
  writeMatches(out, e);
  out << "}";
}

void writeEvaluation(std::ostringstream& out, const change::WorldEvaluation& e) {
  out << "  \"evaluation\": {";
  writeCounts(out, e.totals);
  const change::StaticMapEvaluation& s = e.static_map;
  out << ",\n    \"static_seen_points\": " << s.seen_points
      << ", \"static_completeness\": " << s.completeness
      << ", \"static_mesh_area_m2\": " << s.mesh_area_m2
      << ", \"static_ghost_area_m2\": " << s.ghost_area_m2
      << ", \"static_ghost_share\": " << s.ghostShare() << "},\n";
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
  std::ostringstream out;
  out.precision(6);
  out << std::boolalpha;
  out << "{\n  \"world\": " << jsonString(report.world) << ",\n  \"seed\": " << report.seed
      << ",\n  \"map\": " << jsonString(report.map_config)
      << ",\n  \"device\": " << jsonString(report.device) << ",\n  \"total_s\": " << report.total_s
      << ",\n  \"sessions\": [\n";
  for (std::size_t i = 0; i < report.sessions.size(); ++i) {
    writeSession(out, report.sessions[i], report.evaluation.sessions.at(i));
    out << (i + 1 < report.sessions.size() ? ",\n" : "\n");
  }
  out << "  ],\n";
  writeEvaluation(out, report.evaluation);
  if (!report.incremental_json.empty()) {
    out << "  \"incremental\": " << report.incremental_json << ",\n";
  }
  if (report.alignment) out << "  \"alignment\": " << demoAlignJson(*report.alignment) << ",\n";
  if (!report.objects_json.empty()) out << "  \"objects\": " << report.objects_json << ",\n";
  out << "  \"change_detection\": {\n";
  writeDiffJsonMembers(out, result, files, info, 4);
  out << "\n  }\n}\n";
  const std::string text = out.str();
  writeFileAtomically(path, std::vector<std::uint8_t>(text.begin(), text.end()));
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
  if (!report.objects_summary.empty()) s << " " << report.objects_summary;
  return s.str();
}

}  // namespace strata::apps
