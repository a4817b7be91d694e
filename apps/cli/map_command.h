#pragma once
// `strata map import|info|export`: the map database of many sessions (src/strata/store, docs/store.md).
//   strata map import SESSION_DIR... --db map.sqlite [--keyframe-every N] [--keyframe-distance-m D]
//   strata map info --db map.sqlite [--json] [--verify]
//   strata map export --db map.sqlite --out DIR
// Exit 0 on success, 2 on bad input (missing or damaged database, malformed session folder,
// changed resources with --verify), 1 on other errors (a failed write: full disk, read-only).
#include <string>
#include <vector>

namespace CLI {
class App;
}

namespace strata::apps {

struct MapOptions {
  std::string action;  // "import", "info" or "export" (set by the parsed subcommand)
  std::vector<std::string> session_dirs;
  std::string db_path;
  std::string out_dir;
  int keyframe_every = 10;
  double keyframe_distance_m = 0.0;
  bool json = false;
  bool verify = false;
  bool quiet = false;
};

CLI::App* addMapCommand(CLI::App& app, MapOptions& options);
int runMap(const MapOptions& options);

}  // namespace strata::apps
