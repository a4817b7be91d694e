#pragma once
// `strata drift SRC_DIR --out DIR`: a slice of a TUM RGB-D folder written as a session with
// drifted odometry in a random frame of its own, for alignment tests
// (sim/session/drifted_session.h). The options are checked before the source is read, and --out
// (not the source; a writable folder or a new one in a writable folder) before anything is
// written; a failed run removes the --out folder it made. Exit 0 on success, 2 on bad input
// (missing folder, empty slice, first > last, a bad number, --out over the source), 1 on other
// errors.
#include <cstdint>
#include <string>

#include "strata/sim/session/drifted_session.h"

namespace CLI {
class App;
}

namespace strata::apps {

struct DriftOptions {
  std::string source_dir;
  std::string out_dir;
  std::size_t first_frame = 0;
  long long last_frame = -1;  // < 0: the source's last frame
  sim::DriftedSessionConfig config;
  bool no_offset = false;
};

CLI::App* addDriftCommand(CLI::App& app, DriftOptions& options);
int runDrift(const DriftOptions& options);

}  // namespace strata::apps
