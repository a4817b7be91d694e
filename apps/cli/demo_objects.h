#pragma once
// The demo's last step: the object database over its sessions (cli/objects_outputs.h), its files
// written into the demo's folder and its score against the world's truth into the report.
#include <memory>
#include <string>
#include <vector>

#include "cli/demo_report.h"
#include "strata/mapper/session_diff.h"
#include "strata/sim/world/world.h"

namespace strata::apps {

/// `maps[i]`: session i's own layer; session i of the demo is the world's session i. Sets
/// report.objects, objects_json and objects_summary. Throws on failure.
void addDemoObjects(const DiffResult& result, const std::vector<TsdfMap>& maps,
                    const std::shared_ptr<const sim::World>& world, const std::string& out_dir,
                    DemoReport& report);

}  // namespace strata::apps
