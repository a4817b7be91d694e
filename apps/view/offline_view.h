#pragma once
// What `strata view PATH` serves: a saved map (MAP.strata: its surface, and its ESDF for distance
// queries and slices) or a run folder written by strata demo, diff, objects, align or explore (its
// PLY meshes: static_mesh.ply as the map, session_<s>_mesh.ply as each session's own map (the
// page's colour-by-session view), session_<s>_object_<k>.ply as the objects that moved, with
// their boxes; any other PLY as part of the map; a .strata map in it for the ESDF). Object
// database models (model_<k>.ply, in their own frames), completed scenes and the simulator's true
// meshes (session_<s>_truth.ply) are not shown. Trajectories (TUM: trajectory.txt, *_trajectory.txt,
// as strata align writes per session) and planned paths (strata plan's path.csv) are drawn as
// lines, from the folder and the folders one level down; meshes and maps come from the first of
// those that has any (strata explore writes one folder per planner).
//
// Errors: InputError naming the path when it is missing, neither a map nor a folder, a folder with
// nothing to show, or a file that does not parse; all before the server starts.
// Thread safety: load() once, then answer() from the server's thread only.
#include <memory>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "view/scene.h"

namespace strata {
class Mapper;
namespace vk {
class Context;
}
}  // namespace strata

namespace strata::view {

class OfflineView {
 public:
  /// Reads `path` into `scene` (meshes, objects, a hello message, stats) on the device `device`
  /// ("" = the default) when a map needs one.
  OfflineView(const std::string& path, const std::string& device, Scene& scene);
  ~OfflineView();

  /// A client request: {"type": "query", "id": n, "point": [x, y, z]} -> the distance there;
  /// {"type": "slice", "z": h} -> the ESDF slice at height h (also put in the scene). Without a
  /// map, an "error" message saying so. InputError for a malformed request.
  Message answer(const nlohmann::json& request);

  /// What was loaded, for the command's summary: "3 meshes (412 k triangles), 4 objects, ESDF".
  const std::string& summary() const { return summary_; }
  bool hasEsdf() const { return mapper_ != nullptr; }

 private:
  Scene& scene_;
  std::unique_ptr<vk::Context> context_;
  std::unique_ptr<Mapper> mapper_;
  float voxel_size_m_ = 0.05f;
  float min_x_ = 0, min_y_ = 0, max_x_ = 0, max_y_ = 0;
  std::string summary_;
};

}  // namespace strata::view
