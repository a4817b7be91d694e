#pragma once
// `strata-bench objects`: the object database's matching time against databases of N models
// (src/strata/objects/object_database.h). Models are the simulator's shapes of assorted kinds, sizes and
// colours, each observed completely in an analytic session (objects_scene.h); the queries are
// half views of five of them at new yaws. Per N: prefilter candidates, registrations run and ms
// per segment (observation + matching + merge, median and p90), and how the time grows with N;
// then the cost of one call of each stage (observeObject, registerSurfaces, checkConsistency,
// mergeObservation + refreshModel).
#include <string>
#include <vector>

namespace CLI {
class App;
}

namespace strata::bench {

struct ObjectsBenchOptions {
  std::vector<int> sizes = {1, 5, 10, 25, 50};  // database sizes N
  int yaws = 2;                                 // query views per matched shape
  std::string out_path;                         // also write the JSON here (atomically)
};

CLI::App* addObjectsCommand(CLI::App& app, ObjectsBenchOptions& options);

/// Prints the JSON report; exit code 0, 1 when the self-check failed, 2 bad input.
int runObjectsBench(const ObjectsBenchOptions& options);

}  // namespace strata::bench
