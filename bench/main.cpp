// strata-bench: benchmarks of the Strata engine, one subcommand each, JSON report on stdout and
// progress on stderr.
#include <CLI/CLI.hpp>

#include "diff_command.h"
#include "esdf_command.h"
#include "fuse_command.h"
#include "sim_command.h"

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
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  }
  if (fuse->parsed()) return strata::bench::runFuseBench(fuse_options);
  if (sim->parsed()) return strata::bench::runSimBench(sim_options);
  if (esdf->parsed()) return strata::bench::runEsdfBench(esdf_options);
  if (diff->parsed()) return strata::bench::runDiffBench(diff_options);
  return 2;
}
