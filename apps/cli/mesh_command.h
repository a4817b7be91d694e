#pragma once
// `strata mesh MAP --out mesh.ply`: marching cubes over a saved map. --out is checked (a file in a
// writable folder, not the map) before the map is read. Exit 0 on success, 2 on bad input
// (named), 1 on other errors.
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
