#pragma once
// `strata-bench soak`: strata-mapper (change detection and keyframe scoring on, its defaults) fed
// by strata-play at full speed, session after session of the room for --minutes, both as child
// processes in a private network namespace (udpm://, nothing leaves the machine; needs root).
// The mapper's resident and device memory, map blocks and frame counters are sampled every
// second into DIR/soak.json, plotted in DIR/soak.png, and judged for a plateau (reported only).
#include <string>

namespace CLI {
class App;
}

namespace strata::bench {

struct SoakBenchOptions {
  double minutes = 2.0;
  /// Sessions of the room rendered once up front and replayed in turn: a few, short, so the
  /// loop comes round (and the map stops growing) early in the run.
  int sessions = 3;
  int frames_per_session = 30;
  std::string out_dir = "soak";
  std::string mapper_bin = STRATA_MAPPER_BIN;
  std::string play_bin = STRATA_PLAY_BIN;
  std::string device;
};

CLI::App* addSoakCommand(CLI::App& app, SoakBenchOptions& options);

/// Prints the JSON report; exit code 0, 1 when the run failed (a play or the mapper), 2 bad
/// input (also: no private network namespace), 3 device error.
int runSoakBench(const SoakBenchOptions& options);

}  // namespace strata::bench
