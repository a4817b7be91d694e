#pragma once
// `strata mesh MAP --out mesh.ply`: marching cubes over a saved map.
#include <string>

namespace CLI {
class App;
}

namespace strata::apps {

struct MeshOptions {
  std::string map_path;
  std::string out_path = "mesh.ply";
};

CLI::App* addMeshCommand(CLI::App& app, MeshOptions& options);
int runMesh(const MeshOptions& options);

}  // namespace strata::apps
