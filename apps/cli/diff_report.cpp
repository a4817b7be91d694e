#include "cli/diff_report.h"

#include "core/json_text.h"

#include <cstdio>
#include <sstream>

#include "core/atomic_file.h"

namespace strata::apps {
namespace {

std::string vec3(const Eigen::Vector3f& v) {
  std::ostringstream out;
  out.precision(4);
  out << "[" << v.x() << ", " << v.y() << ", " << v.z() << "]";
  return out.str();
}

void writeObject(std::ostream& out, const change::DiscoveredObject& o, const std::string& file,
                 const std::string& pad) {
  out << pad << "{\"id\": " << o.id << ", \"vertices\": " << o.vertex_count
      << ", \"triangles\": " << o.mesh.triangles.size() << ", \"centroid_m\": " << vec3(o.centroid)
      << ", \"bbox_min_m\": " << vec3(o.bbox.min()) << ", \"bbox_max_m\": " << vec3(o.bbox.max())
      << ", \"mesh\": " << jsonString(file) << "}";
}

void writeSession(std::ostream& out, std::size_t s, const DiffResult& result,
                  const DiffFiles& files, const std::string& pad) {
  const DiffSession& r = result.sessions[s];
  const double n = r.frames > 0 ? static_cast<double>(r.frames) : 1.0;
  out << pad << "{\"session\": " << s << ", \"source\": " << jsonString(r.source)
      << ", \"frames\": " << r.frames << ", \"fuse_wall_ms_per_frame\": " << r.fuse_wall_ms / n
      << ", \"fuse_device_ms_per_frame\": " << r.fuse_device_ms / n
      << ", \"update_ms\": " << r.update.stages.total() << ", \"blocks\": " << r.update.blocks
      << ", \"dynamic_voxels\": " << r.update.dynamic_voxels
      << ", \"surface_faces\": " << r.object_stats.faces
      << ", \"dynamic_faces\": " << r.object_stats.dynamic_faces_refined
      << ", \"dropped_planar\": " << r.object_stats.dropped_planar
      << ", \"dropped_small\": " << r.object_stats.dropped_small
      << ", \"overlay\": " << jsonString(files.overlays[s]) << ",\n"
      << pad << " \"objects\": [";
  for (std::size_t k = 0; k < r.objects.size(); ++k) {
    out << (k ? ",\n" : "\n");
    writeObject(out, r.objects[k], files.object_meshes[s][k], pad + "   ");
  }
  out << (r.objects.empty() ? "]}" : "\n" + pad + " ]}");
}

}  // namespace

std::string jsonString(const std::string& text) { return jsonQuoted(text); }

void writeDiffJsonMembers(std::ostream& out, const DiffResult& result, const DiffFiles& files,
                          const DiffRunInfo& info, int indent) {
  const std::string pad(static_cast<std::size_t>(indent), ' ');
  const change::ChangeConfig& c = info.change;
  const change::ObjectConfig& o = info.objects;
  out << pad << "\"change_config\": {\"min_weight\": " << c.min_weight
      << ", \"difference_threshold_m\": " << c.difference_threshold_m
      << ", \"erosion_kernel_voxels\": " << c.erosion_kernel_voxels
      << ", \"dilation_kernel_voxels\": " << c.dilation_kernel_voxels
      << ", \"merge_close_m\": " << c.merge_close_m << "},\n"
      << pad
      << "\"object_config\": {\"region_neighbour_angle_deg\": " << o.region_neighbour_angle_deg
      << ", \"region_mean_angle_deg\": " << o.region_mean_angle_deg
      << ", \"region_dynamic_share\": " << o.region_dynamic_share
      << ", \"component_merge_gap_voxels\": " << o.component_merge_gap_voxels
      << ", \"min_singular_value_ratio\": " << o.min_singular_value_ratio
      << ", \"min_vertices\": " << o.min_vertices << "},\n"
      << pad << "\"static_mesh\": {\"vertices\": " << result.static_mesh.vertices.size()
      << ", \"triangles\": " << result.static_mesh.triangles.size()
      << ", \"mesh\": " << jsonString(files.static_mesh) << "},\n"
      << pad << "\"sessions\": [\n";
  for (std::size_t s = 0; s < result.sessions.size(); ++s) {
    writeSession(out, s, result, files, pad + "  ");
    out << (s + 1 < result.sessions.size() ? ",\n" : "\n");
  }
  out << pad << "]";
}

void writeDiffReport(const std::string& path, const DiffResult& result, const DiffFiles& files,
                     const DiffRunInfo& info) {
  std::ostringstream out;
  out.precision(6);
  out << "{\n  \"command\": \"diff\",\n  \"device\": " << jsonString(info.device)
      << ",\n  \"map\": " << jsonString(info.map_config) << ",\n  \"total_s\": " << info.total_s
      << ",\n  \"objects_s\": " << result.objects_s << ",\n";
  writeDiffJsonMembers(out, result, files, info, 2);
  out << "\n}\n";
  const std::string text = out.str();
  writeFileAtomically(path, std::vector<std::uint8_t>(text.begin(), text.end()));
}

std::string summarizeDiff(const DiffResult& result, const DiffRunInfo& info,
                          const std::string& out_dir) {
  std::size_t frames = 0, objects = 0;
  for (const DiffSession& s : result.sessions) {
    frames += s.frames;
    objects += s.objects.size();
  }
  std::ostringstream s;
  s.precision(3);
  s << "Compared " << result.sessions.size() << " sessions (" << frames << " frames fused) in "
    << info.total_s << " s on " << info.device << " (" << info.map_config
    << "). The static map has " << result.static_mesh.vertices.size() << " mesh vertices. ";
  for (std::size_t i = 0; i < result.sessions.size(); ++i) {
    const DiffSession& r = result.sessions[i];
    s << "Session " << i << " (" << r.source << "): " << r.objects.size() << " changed object"
      << (r.objects.size() == 1 ? "" : "s");
    if (!r.objects.empty()) {
      s << " (largest " << r.objects.front().vertex_count << " vertices at "
        << r.objects.front().centroid.x() << ", " << r.objects.front().centroid.y() << " m)";
    }
    s << ". ";
  }
  s << "Wrote static_mesh.ply, " << objects << " object meshes, one label overlay per session and "
    << "report.json to " << out_dir << "/.";
  return s.str();
}

}  // namespace strata::apps
