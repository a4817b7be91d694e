#include "cli/mesh_command.h"

#include <CLI/CLI.hpp>

#include <cstdio>

#include "strata/core/error.h"
#include "strata/core/output_paths.h"
#include "strata/map/map_file.h"
#include "strata/mesh/extract_mesh.h"
#include "strata/mesh/ply.h"

namespace strata::apps {

CLI::App* addMeshCommand(CLI::App& app, MeshOptions& o) {
  CLI::App* mesh = app.add_subcommand("mesh", "Extract a mesh from a saved map");
  mesh->add_option("map", o.map_path, "Map file (.strata)")->required();
  mesh->add_option("--out", o.out_path, "Output PLY")->capture_default_str();
  return mesh;
}

int runMesh(const MeshOptions& o) {
  try {
    if (o.map_path.empty()) throw InputError("no map file given");
    if (o.out_path.empty()) throw InputError("--out must name a file");
    OutputPaths paths;
    paths.inputFile(o.map_path, "the map");
    paths.outputFile(o.out_path, "--out");
    paths.check();
    const TsdfMap map = loadMap(o.map_path);
    const Mesh mesh = extractMesh(map);
    writePly(o.out_path, mesh);
    std::printf("Meshed %zu blocks of '%s' into %zu vertices and %zu triangles; wrote %s.\n",
                map.blockCount(), o.map_path.c_str(), mesh.vertices.size(), mesh.triangles.size(),
                o.out_path.c_str());
    return 0;
  } catch (const InputError& e) {
    std::fprintf(stderr, "strata mesh: input error: %s\n", e.what());
    return 2;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "strata mesh: error: %s\n", e.what());
    return 1;
  }
}

}  // namespace strata::apps
