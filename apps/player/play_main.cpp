// strata-play DATASET: replays a TUM RGB-D folder or a synthetic world session over LCM, at real
// time (--rate 1) or as fast as strata-mapper fuses (--rate 0, flow control by its stats).
#include <CLI/CLI.hpp>

#include "cli/option_checks.h"
#include "player/play_options.h"
#include "player/play_run.h"

int main(int argc, char** argv) {
  CLI::App app{"strata-play: replay an RGB-D dataset or synthetic session over LCM"};
  strata::apps::PlayOptions options;
  strata::apps::addPlayOptions(app, options);
  int exit_code = 0;
  if (!strata::apps::parseCommandLine(app, argc, argv, &exit_code)) return exit_code;
  return strata::apps::runPlay(options);
}
