// strata: the command-line entry point. With no subcommand it runs the main job on the built-in
// default data: fuse the analytic scene and write mesh, map and a rendering to strata_out/.
#include <CLI/CLI.hpp>

#include <cstdio>
#include <filesystem>

#include "apps/fuse_command.h"
#include "apps/mesh_command.h"
#include "core/error.h"
#include "vk/vk.h"

namespace {

int listDevices() {
  try {
    for (const auto& device : strata::vk::Context::listDevices()) {
      std::printf("%u: %s\n", device.index, device.name.c_str());
    }
    return 0;
  } catch (const strata::Error& e) {
    std::fprintf(stderr, "strata devices: %s\n", e.what());
    return 3;
  }
}

int runDefault() {
  const std::string out_dir = "strata_out";
  std::filesystem::create_directories(out_dir);
  strata::apps::FuseOptions options;
  options.mesh_path = out_dir + "/analytic_mesh.ply";
  options.map_path = out_dir + "/analytic_map.strata";
  options.render_path = out_dir + "/analytic_view.png";
  std::printf("strata: no command given; fusing the built-in analytic scene into %s/\n",
              out_dir.c_str());
  return strata::apps::runFuse(options);
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Strata: dense multi-session mapping on Vulkan compute"};
  app.require_subcommand(0, 1);
  strata::apps::FuseOptions fuse_options;
  CLI::App* fuse = strata::apps::addFuseCommand(app, fuse_options);
  strata::apps::MeshOptions mesh_options;
  CLI::App* mesh = strata::apps::addMeshCommand(app, mesh_options);
  CLI::App* devices = app.add_subcommand("devices", "List the Vulkan devices");
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  }
  if (fuse->parsed()) return strata::apps::runFuse(fuse_options);
  if (mesh->parsed()) return strata::apps::runMesh(mesh_options);
  if (devices->parsed()) return listDevices();
  return runDefault();
}
