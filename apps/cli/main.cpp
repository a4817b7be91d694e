// strata: the command-line entry point. With no subcommand it runs the main job on the built-in
// default data: the multi-session demo on the shipped single-room world (strata_out/).
#include <CLI/CLI.hpp>
#include <cstdio>

#include "cli/option_checks.h"
#include "cli/align_command.h"
#include "cli/localize_command.h"
#include "cli/demo_command.h"
#include "cli/diff_command.h"
#include "cli/drift_command.h"
#include "cli/esdf_command.h"
#include "cli/eval_trajectory_command.h"
#include "cli/explore_command.h"
#include "cli/repeat_command.h"
#include "cli/teach_command.h"
#include "cli/fuse_command.h"
#include "cli/map_command.h"
#include "cli/mesh_command.h"
#include "cli/objects_command.h"
#include "cli/odometry_command.h"
#include "cli/plan_command.h"
#include "cli/select_command.h"
#include "cli/sim_command.h"
#include "cli/topo_command.h"
#include "strata/core/error.h"
#include "view/view_command.h"
#include "strata/vk/vk.h"

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
  std::printf(
      "strata: no command given; running the multi-session demo on the shipped room "
      "(see `strata --help` for fuse, sim, demo, diff, drift, mesh, esdf, select, eval-trajectory, "
      "map, odometry, align, localize, objects, plan, topo, explore, teach, repeat, view, devices)\n");
  return strata::apps::runDemo(strata::apps::DemoOptions{});
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Strata: dense multi-session mapping on Vulkan compute"};
  app.require_subcommand(0, 1);
  strata::apps::FuseOptions fuse_options;
  CLI::App* fuse = strata::apps::addFuseCommand(app, fuse_options);
  strata::apps::MeshOptions mesh_options;
  CLI::App* mesh = strata::apps::addMeshCommand(app, mesh_options);
  strata::apps::SimOptions sim_options;
  CLI::App* sim = strata::apps::addSimCommand(app, sim_options);
  strata::apps::DemoOptions demo_options;
  CLI::App* demo = strata::apps::addDemoCommand(app, demo_options);
  strata::apps::DiffOptions diff_options;
  CLI::App* diff = strata::apps::addDiffCommand(app, diff_options);
  strata::apps::DriftOptions drift_options;
  CLI::App* drift = strata::apps::addDriftCommand(app, drift_options);
  strata::apps::EsdfOptions esdf_options;
  CLI::App* esdf = strata::apps::addEsdfCommand(app, esdf_options);
  strata::apps::SelectOptions select_options;
  CLI::App* select_cmd = strata::apps::addSelectCommand(app, select_options);
  strata::apps::EvalTrajectoryOptions eval_trajectory_options;
  CLI::App* eval_trajectory = strata::apps::addEvalTrajectoryCommand(app, eval_trajectory_options);
  strata::apps::MapOptions map_options;
  CLI::App* map = strata::apps::addMapCommand(app, map_options);
  strata::apps::OdometryOptions odometry_options;
  CLI::App* odometry = strata::apps::addOdometryCommand(app, odometry_options);
  strata::apps::AlignOptions align_options;
  CLI::App* align = strata::apps::addAlignCommand(app, align_options);
  strata::apps::LocalizeOptions localize_options;
  CLI::App* localize = strata::apps::addLocalizeCommand(app, localize_options);
  strata::apps::ObjectsOptions objects_options;
  CLI::App* objects = strata::apps::addObjectsCommand(app, objects_options);
  strata::apps::PlanOptions plan_options;
  CLI::App* plan = strata::apps::addPlanCommand(app, plan_options);
  strata::apps::TopoOptions topo_options;
  CLI::App* topo = strata::apps::addTopoCommand(app, topo_options);
  strata::apps::ExploreOptions explore_options;
  CLI::App* explore = strata::apps::addExploreCommand(app, explore_options);
  strata::apps::TeachOptions teach_options;
  CLI::App* teach = strata::apps::addTeachCommand(app, teach_options);
  strata::apps::RepeatOptions repeat_options;
  CLI::App* repeat = strata::apps::addRepeatCommand(app, repeat_options);
  strata::apps::ViewOptions view_options;
  CLI::App* view = strata::apps::addViewCommand(app, view_options);
  CLI::App* devices = app.add_subcommand("devices", "List the Vulkan devices");
  int exit_code = 0;
  if (!strata::apps::parseCommandLine(app, argc, argv, &exit_code)) return exit_code;
  if (fuse->parsed()) return strata::apps::runFuse(fuse_options);
  if (mesh->parsed()) return strata::apps::runMesh(mesh_options);
  if (sim->parsed()) return strata::apps::runSim(sim_options);
  if (demo->parsed()) return strata::apps::runDemo(demo_options);
  if (diff->parsed()) return strata::apps::runDiff(diff_options);
  if (drift->parsed()) return strata::apps::runDrift(drift_options);
  if (esdf->parsed()) return strata::apps::runEsdf(esdf_options);
  if (select_cmd->parsed()) return strata::apps::runSelect(select_options);
  if (eval_trajectory->parsed()) return strata::apps::runEvalTrajectory(eval_trajectory_options);
  if (map->parsed()) return strata::apps::runMap(map_options);
  if (odometry->parsed()) return strata::apps::runOdometry(odometry_options);
  if (align->parsed()) return strata::apps::runAlign(align_options);
  if (localize->parsed()) return strata::apps::runLocalize(localize_options);
  if (objects->parsed()) return strata::apps::runObjects(objects_options);
  if (plan->parsed()) return strata::apps::runPlan(plan_options);
  if (topo->parsed()) return strata::apps::runTopo(topo_options);
  if (explore->parsed()) return strata::apps::runExplore(explore_options);
  if (teach->parsed()) return strata::apps::runTeach(teach_options);
  if (repeat->parsed()) return strata::apps::runRepeatCommand(repeat_options);
  if (view->parsed()) return strata::apps::runView(view_options);
  if (devices->parsed()) return listDevices();
  return runDefault();
}
