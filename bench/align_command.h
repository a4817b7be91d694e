#pragma once
// `strata-bench align`: multi-session alignment (align/session_alignment.h) on simulated sessions
// in memory: each session's drifting odometry in a frame of its own, every frame a keyframe.
// Reports the time of each stage per keyframe (features, place index, verification, pose graph)
// and the result against the simulator's truth.
#include <string>

namespace CLI {
class App;
}

namespace strata::bench {

struct AlignBenchOptions {
  std::string world = "room";  // a shipped world's name
  int sessions = 3;
  int frames = 100;            // per session, spread over its path
  bool flat_color = false;     // the simulator's flat-shaded RGB instead of the textured one
  int threads = 2;
  std::string out_path;        // also write the JSON here (atomically)
};

CLI::App* addAlignCommand(CLI::App& app, AlignBenchOptions& options);

/// Prints the JSON report; exit code 0, 2 bad input, 1 other failures.
int runAlignBench(const AlignBenchOptions& options);

}  // namespace strata::bench
