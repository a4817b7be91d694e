#pragma once
// The runs of `strata-bench diff` (diff_command.h): sessions fused and ended on the device, the
// same session maps through the C++ reference, reported per session.
#include <memory>
#include <string>
#include <vector>

#include "strata/change/change_detector.h"
#include "json.h"
#include "strata/sim/world/world.h"

namespace strata::bench {

struct DiffSessionRun {
  int session = 0;
  std::size_t frames = 0;
  double fusion_device_ms = 0.0;  // normals + allocation + integration, all frames
  change::ChangeUpdateStats device;
  change::ChangeUpdateStats reference;  // session < 0 when not run
  double label_agreement = 1.0;         // D, device vs reference
  double part_agreement = 1.0;          // the session's dynamic part
};

struct DiffRun {
  std::string device_name;
  std::uint64_t device_bytes = 0;  // the map's layers, hash table and counters at the end
  std::vector<DiffSessionRun> sessions;
  bool ok = true;
};

struct DiffRunSettings {
  std::shared_ptr<const sim::World> world;
  int sessions = 0;
  int frames = 0;
  MapConfig map;
  change::ChangeConfig change;
  bool reference = true;
  std::string device;
};

DiffRun runDiff(const DiffRunSettings& settings);

/// One session's report: stage times, per voxel, reference, agreement.
Json diffSessionJson(const DiffSessionRun& run);
/// Means over sessions of the device and reference stage times (ms) and ns per voxel.
Json diffSummaryJson(const DiffRun& run);

}  // namespace strata::bench
