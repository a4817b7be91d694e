// strata-localizer: localisation against a prior map over LCM. Loads the prior map of a map
// database (read-only), subscribes RGB-D frames and the odometry's poses (strata-vio's), localises
// every Nth frame on a worker thread, fuses the localisations with the odometry and publishes the
// camera's pose in the map frame for every odometry pose (strata-mapper can take them: its
// --pose-channel) and a status per frame. A progress line goes to stderr every few seconds, a
// summary at exit (SIGINT/SIGTERM, or --max-idle-s after the streams stop), a JSON report to
// --report. Exit codes: 0; 2 bad input (options, a missing, corrupt or newer map database, a map
// without a usable keyframe, --report's path), before subscribing; 1 other errors.
#include <CLI/CLI.hpp>
#include <atomic>
#include <cstdio>
#include <memory>
#include <string>

#include "cli/option_checks.h"
#include "localizer_node/localizer_core.h"
#include "localizer_node/localizer_node.h"
#include "strata/core/atomic_file.h"
#include "strata/core/error.h"
#include "strata/core/output_paths.h"
#include "strata/lcm/stop_signal.h"

namespace {

int runLocalizer(const strata::apps::LocalizerOptions& options, const std::atomic<bool>& stop) {
  using namespace strata;
  options.validate();
  OutputPaths paths;
  paths.inputFile(options.db_path, "--db");
  paths.outputFile(options.report_path, "--report");
  paths.check();
  // The LCM URLs first (a bad one is refused before seconds of loading), subscriptions last.
  lcm::LCM input(options.url);
  if (!input.good()) throw InputError("LCM input '" + options.url + "' could not be opened");
  std::unique_ptr<lcm::LCM> separate_output;
  if (!options.output_url.empty()) separate_output = std::make_unique<lcm::LCM>(options.output_url);
  if (separate_output && !separate_output->good()) {
    throw InputError("LCM output '" + options.output_url + "' could not be opened");
  }
  const localize::PriorMap map = apps::loadPriorMap(options);  // before subscribing
  apps::LocalizerCore core(map, options);
  apps::LocalizerNode node(input, separate_output ? *separate_output : input, core, options);
  const apps::LocalizerChannels& c = options.channels;
  std::fprintf(stderr,
               "strata-localizer: listening on %s (frames %s, camera info %s, odometry %s); "
               "map-frame poses on %s, status on %s; localising 1 frame in %d\n",
               options.url.c_str(), c.rgbd.c_str(), c.camera_info.c_str(), c.odometry.c_str(),
               c.pose.c_str(), c.status.c_str(), options.every);
  const apps::LocalizerSnapshot s = node.run(stop);
  if (!options.report_path.empty()) {
    writeTextAtomically(
        options.report_path,
        apps::localizerReportJson(s, options.db_path, options.every, map.keyframes().size()));
  }
  std::fputs(apps::localizerSummary(s).c_str(), stdout);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{
      "strata-localizer: localise live RGB-D frames against a prior map (a map database) and "
      "publish the odometry's poses in the map frame"};
  strata::apps::LocalizerOptions options;
  strata::apps::addLocalizerOptions(app, options);
  int exit_code = 0;
  if (!strata::apps::parseCommandLine(app, argc, argv, &exit_code)) return exit_code;
  const std::atomic<bool>& stop = strata::lcm_io::installStopSignals();
  try {
    return runLocalizer(options, stop);
  } catch (const strata::InputError& e) {
    std::fprintf(stderr, "strata-localizer: input error: %s\n", e.what());
    return 2;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "strata-localizer: error: %s\n", e.what());
    return 1;
  }
}
