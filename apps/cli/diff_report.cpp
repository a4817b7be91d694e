#include "cli/diff_report.h"

#include <cstdio>
#include <sstream>

#include "cli/report_json.h"
#include "strata/core/atomic_file.h"

namespace strata::apps {
namespace {

Json objectJson(const change::DiscoveredObject& o, const std::string& file) {
  Json j;
  j["id"] = o.id;
  j["vertices"] = o.vertex_count;
  j["triangles"] = o.mesh.triangles.size();
  j["centroid_m"] = jsonVector(o.centroid);
  j["bbox_min_m"] = jsonVector(o.bbox.min());
  j["bbox_max_m"] = jsonVector(o.bbox.max());
  j["mesh"] = file;
  return j;
}

Json diffSessionJson(std::size_t s, const DiffResult& result, const DiffFiles& files) {
  const DiffSession& r = result.sessions[s];
  const double n = r.frames > 0 ? static_cast<double>(r.frames) : 1.0;
  Json objects = Json::array();
  for (std::size_t k = 0; k < r.objects.size(); ++k) {
    objects.push_back(objectJson(r.objects[k], files.object_meshes[s][k]));
  }
  Json j;
  j["session"] = s;
  j["source"] = r.source;
  j["frames"] = r.frames;
  j["fuse_wall_ms_per_frame"] = r.fuse_wall_ms / n;
  j["fuse_device_ms_per_frame"] = r.fuse_device_ms / n;
  j["update_ms"] = r.update.stages.total();
  j["blocks"] = r.update.blocks;
  j["dynamic_voxels"] = r.update.dynamic_voxels;
  j["surface_faces"] = r.object_stats.faces;
  j["dynamic_faces"] = r.object_stats.dynamic_faces_refined;
  j["dropped_planar"] = r.object_stats.dropped_planar;
  j["dropped_small"] = r.object_stats.dropped_small;
  j["overlay"] = files.overlays[s];
  j["objects"] = std::move(objects);
  return j;
}

Json changeConfigJson(const change::ChangeConfig& c) {
  Json j;
  j["min_weight"] = jsonFloat(c.min_weight);
  j["difference_threshold_m"] = jsonFloat(c.difference_threshold_m);
  j["erosion_kernel_voxels"] = c.erosion_kernel_voxels;
  j["dilation_kernel_voxels"] = c.dilation_kernel_voxels;
  j["merge_close_m"] = jsonFloat(c.merge_close_m);
  return j;
}

Json objectConfigJson(const change::ObjectConfig& o) {
  Json j;
  j["region_neighbour_angle_deg"] = jsonFloat(o.region_neighbour_angle_deg);
  j["region_mean_angle_deg"] = jsonFloat(o.region_mean_angle_deg);
  j["region_dynamic_share"] = jsonFloat(o.region_dynamic_share);
  j["component_merge_gap_voxels"] = jsonFloat(o.component_merge_gap_voxels);
  j["min_singular_value_ratio"] = jsonFloat(o.min_singular_value_ratio);
  j["min_vertices"] = o.min_vertices;
  return j;
}

/// Adds the members diffReportJson describes to `j`.
void addDiffMembers(const DiffResult& result, const DiffFiles& files, const DiffRunInfo& info,
                    Json& j) {
  Json static_mesh;
  static_mesh["vertices"] = result.static_mesh.vertices.size();
  static_mesh["triangles"] = result.static_mesh.triangles.size();
  static_mesh["mesh"] = files.static_mesh;
  Json sessions = Json::array();
  for (std::size_t s = 0; s < result.sessions.size(); ++s) {
    sessions.push_back(diffSessionJson(s, result, files));
  }
  j["change_config"] = changeConfigJson(info.change);
  j["object_config"] = objectConfigJson(info.objects);
  j["static_mesh"] = std::move(static_mesh);
  j["sessions"] = std::move(sessions);
}

}  // namespace

std::string diffReportJson(const DiffResult& result, const DiffFiles& files,
                           const DiffRunInfo& info) {
  Json j = Json::object();
  addDiffMembers(result, files, info, j);
  return jsonText(j);
}

void writeDiffReport(const std::string& path, const DiffResult& result, const DiffFiles& files,
                     const DiffRunInfo& info) {
  Json j;
  j["command"] = "diff";
  j["device"] = info.device;
  j["map"] = info.map_config;
  j["total_s"] = info.total_s;
  j["objects_s"] = result.objects_s;
  addDiffMembers(result, files, info, j);
  writeTextAtomically(path, jsonFileText(j));
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
