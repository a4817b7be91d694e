#include "apps/demo_report.h"

#include <sstream>

#include "core/atomic_file.h"

namespace strata::apps {
namespace {

std::string idList(const std::vector<int>& ids) {
  std::ostringstream out;
  out << "[";
  for (std::size_t i = 0; i < ids.size(); ++i) out << (i ? ", " : "") << ids[i];
  out << "]";
  return out.str();
}

void writeSession(std::ostringstream& out, const SessionResult& r) {
  const double n = r.frames > 0 ? static_cast<double>(r.frames) : 1.0;
  out << "    {\"session\": " << r.session << ", \"frames\": " << r.frames
      << ", \"render_fps\": " << (r.render_s > 0 ? r.frames / r.render_s : 0.0)
      << ", \"fuse_wall_ms_per_frame\": " << r.fuse_wall_ms / n
      << ", \"fuse_device_ms_per_frame\": " << r.fuse_device_ms / n << ", \"blocks\": " << r.blocks
      << ", \"tsdf_mean_abs_error_m\": " << r.tsdf.mean_abs_error_m
      << ", \"tsdf_voxels_compared\": " << r.tsdf.voxels
      << ", \"mesh_vertices\": " << r.mesh_vertices
      << ", \"mesh_mean_distance_m\": " << r.mesh.mean_distance_m
      << ", \"mesh_p99_distance_m\": " << r.mesh.p99_distance_m
      << ", \"mesh_fraction_within_voxel\": " << r.mesh.fraction_within
      << ", \"changed_object_ids\": " << idList(r.changed_ids) << "}";
}

}  // namespace

void writeDemoReport(const DemoReport& report, const std::string& path) {
  std::ostringstream out;
  out.precision(6);
  out << "{\n  \"world\": \"" << report.world << "\",\n  \"seed\": " << report.seed
      << ",\n  \"map\": \"" << report.map_config << "\",\n  \"device\": \"" << report.device
      << "\",\n  \"total_s\": " << report.total_s << ",\n  \"sessions\": [\n";
  for (std::size_t i = 0; i < report.sessions.size(); ++i) {
    writeSession(out, report.sessions[i]);
    out << (i + 1 < report.sessions.size() ? ",\n" : "\n");
  }
  out << "  ]\n}\n";
  const std::string text = out.str();
  writeFileAtomically(path, std::vector<std::uint8_t>(text.begin(), text.end()));
}

std::string summarizeDemo(const DemoReport& report, const std::string& out_dir) {
  std::size_t frames = 0;
  double render_s = 0.0, fuse_ms = 0.0, tsdf_error = 0.0, within = 0.0;
  for (const SessionResult& r : report.sessions) {
    frames += r.frames;
    render_s += r.render_s;
    fuse_ms += r.fuse_wall_ms;
    tsdf_error += r.tsdf.mean_abs_error_m;
    within += r.mesh.fraction_within;
  }
  const double sessions = report.sessions.empty() ? 1.0 : double(report.sessions.size());
  std::ostringstream s;
  s.precision(3);
  s << "Simulated and fused " << report.sessions.size() << " sessions of world '" << report.world
    << "' (seed " << report.seed << "), " << frames << " frames, in " << report.total_s
    << " s on " << report.device << " (" << report.map_config << "): rendering "
    << (render_s > 0 ? frames / render_s : 0.0) << " frames/s, fusion "
    << (frames > 0 ? fuse_ms / frames : 0.0) << " ms/frame. Against the ground truth: mean "
    << "|TSDF - SDF| " << 1000.0 * tsdf_error / sessions << " mm near surfaces, "
    << 100.0 * within / sessions << " % of mesh vertices within one voxel of the true surface. ";
  for (const SessionResult& r : report.sessions) {
    if (r.session > 0) s << "Session " << r.session << " changed objects " << idList(r.changed_ids) << ". ";
  }
  s << "Wrote per-session meshes (fused and true) and report.json to " << out_dir << "/.";
  return s.str();
}

}  // namespace strata::apps
