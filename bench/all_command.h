#pragma once
// `strata-bench all --out DIR`: every benchmark, each in a child process of its own (so peak
// memory and warm-up are per benchmark), into DIR/<name>.json, then one DIR/all.json with the
// machine header and every report, PNG plots of the fusion figures and DIR/summary.md.
#include <string>
#include <vector>

namespace CLI {
class App;
}

namespace strata::bench {

struct AllBenchOptions {
  std::string out_dir;                      // required; created when missing
  std::vector<std::string> only;            // benchmark names; empty: all
  std::vector<int> map_size_prefill{10000, 40000};  // extra fuse runs at 2 cm (map-size plot)
  int fuse_frames = 0;                      // forwarded as `fuse --frames` (0: all)
  std::string device;                       // forwarded as --device
};

CLI::App* addAllCommand(CLI::App& app, AllBenchOptions& options);

/// 0 when every benchmark exited 0; 1 when one failed (the others still run and the summary
/// says which); 2 bad input.
int runAllBench(const AllBenchOptions& options);

}  // namespace strata::bench
