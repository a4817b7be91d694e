#include "cli/diff_outputs.h"

#include <filesystem>

#include "cli/diff_overlay.h"
#include "strata/mesh/ply.h"

namespace strata::apps {

DiffFiles writeDiffFiles(const DiffResult& result, const std::string& out_dir) {
  namespace fs = std::filesystem;
  const fs::path out(out_dir);
  DiffFiles files;
  files.static_mesh = (out / "static_mesh.ply").string();
  writePly(files.static_mesh, result.static_mesh);
  for (std::size_t s = 0; s < result.sessions.size(); ++s) {
    const DiffSession& session = result.sessions[s];
    const std::string stem = "session_" + std::to_string(s);
    files.object_meshes.emplace_back();
    for (const change::DiscoveredObject& object : session.objects) {
      files.object_meshes.back().push_back(
          (out / (stem + "_object_" + std::to_string(object.id) + ".ply")).string());
      writePly(files.object_meshes.back().back(), object.mesh);
    }
    files.overlays.emplace_back();
    if (session.surface.mesh.empty()) continue;  // nothing observed: no picture to draw
    OverlayOptions options;
    options.title = "SESSION " + std::to_string(s) + ": " + std::to_string(session.objects.size()) +
                    " CHANGED OBJECTS, SEEN FROM ABOVE";
    files.overlays.back() = (out / (stem + "_overlay.png")).string();
    writeOverlayPng(files.overlays.back(), session.surface.mesh, session.objects, options);
  }
  return files;
}

}  // namespace strata::apps
