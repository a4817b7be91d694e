// strata-bench: benchmarks of the Strata engine, one subcommand each, JSON report on stdout and
// progress on stderr.
#include <CLI/CLI.hpp>

#include "all_command.h"
#include "diff_command.h"
#include "esdf_command.h"
#include "explore_gain_command.h"
#include "plan_command.h"
#include "frontend_command.h"
#include "fuse_command.h"
#include "lcm_command.h"
#include "select_command.h"
#include "occupancy_command.h"
#include "plan_collision_command.h"
#include "align_command.h"
#include "objects_command.h"
#include "posegraph_command.h"
#include "sim_command.h"
#include "soak_command.h"
#include "vio_command.h"
#include "track_command.h"

int main(int argc, char** argv) {
  CLI::App app{"strata-bench: Strata benchmarks (JSON on stdout, progress on stderr)"};
  app.require_subcommand(1);
  strata::bench::FuseBenchOptions fuse_options;
  CLI::App* fuse = strata::bench::addFuseCommand(app, fuse_options);
  strata::bench::SimBenchOptions sim_options;
  CLI::App* sim = strata::bench::addSimCommand(app, sim_options);
  strata::bench::EsdfBenchOptions esdf_options;
  CLI::App* esdf = strata::bench::addEsdfCommand(app, esdf_options);
  strata::bench::DiffBenchOptions diff_options;
  CLI::App* diff = strata::bench::addDiffCommand(app, diff_options);
  strata::bench::SelectBenchOptions select_options;
  CLI::App* select_cmd = strata::bench::addSelectCommand(app, select_options);
  strata::bench::ExploreGainBenchOptions explore_gain_options;
  CLI::App* explore_gain = strata::bench::addExploreGainCommand(app, explore_gain_options);
  strata::bench::OccupancyBenchOptions occupancy_options;
  CLI::App* occupancy = strata::bench::addOccupancyCommand(app, occupancy_options);
  strata::bench::LcmBenchOptions lcm_options;
  CLI::App* lcm = strata::bench::addLcmCommand(app, lcm_options);
  strata::bench::SoakBenchOptions soak_options;
  CLI::App* soak = strata::bench::addSoakCommand(app, soak_options);
  strata::bench::VioBenchOptions vio_options;
  CLI::App* vio = strata::bench::addVioCommand(app, vio_options);
  strata::bench::TrackBenchOptions track_options;
  CLI::App* track = strata::bench::addTrackCommand(app, track_options);
  strata::bench::FrontendBenchOptions frontend_options;
  CLI::App* frontend = strata::bench::addFrontendCommand(app, frontend_options);
  strata::bench::AlignBenchOptions align_options;
  CLI::App* align = strata::bench::addAlignCommand(app, align_options);
  strata::bench::PoseGraphBenchOptions posegraph_options;
  CLI::App* posegraph = strata::bench::addPoseGraphCommand(app, posegraph_options);
  strata::bench::ObjectsBenchOptions objects_options;
  CLI::App* objects = strata::bench::addObjectsCommand(app, objects_options);
  strata::bench::PlanCollisionBenchOptions plan_collision_options;
  CLI::App* plan_collision = strata::bench::addPlanCollisionCommand(app, plan_collision_options);
  strata::bench::PlanBenchOptions plan_options;
  CLI::App* plan = strata::bench::addPlanCommand(app, plan_options);
  strata::bench::AllBenchOptions all_options;
  CLI::App* all = strata::bench::addAllCommand(app, all_options);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  }
  if (fuse->parsed()) return strata::bench::runFuseBench(fuse_options);
  if (sim->parsed()) return strata::bench::runSimBench(sim_options);
  if (esdf->parsed()) return strata::bench::runEsdfBench(esdf_options);
  if (plan->parsed()) return strata::bench::runPlanBench(plan_options);
  if (diff->parsed()) return strata::bench::runDiffBench(diff_options);
  if (select_cmd->parsed()) return strata::bench::runSelectBench(select_options);
  if (explore_gain->parsed()) return strata::bench::runExploreGainBench(explore_gain_options);
  if (occupancy->parsed()) return strata::bench::runOccupancyBench(occupancy_options);
  if (lcm->parsed()) return strata::bench::runLcmBench(lcm_options);
  if (soak->parsed()) return strata::bench::runSoakBench(soak_options);
  if (vio->parsed()) return strata::bench::runVioBench(vio_options);
  if (track->parsed()) return strata::bench::runTrackBench(track_options);
  if (frontend->parsed()) return strata::bench::runFrontendBench(frontend_options);
  if (posegraph->parsed()) return strata::bench::runPoseGraphBench(posegraph_options);
  if (align->parsed()) return strata::bench::runAlignBench(align_options);
  if (objects->parsed()) return strata::bench::runObjectsBench(objects_options);
  if (plan_collision->parsed()) {
    return strata::bench::runPlanCollisionBench(plan_collision_options);
  }
  if (all->parsed()) return strata::bench::runAllBench(all_options);
  return 2;
}
