#pragma once
// The measured runs of `strata-bench esdf` on one input: fusion with the ESDF updated
// incrementally after every frame, full recomputations, the C++ reference, planner queries (host
// and device) and the slice picture, with the JSON report of each.
#include <cstdint>
#include <string>
#include <vector>

#include "strata/io/open_dataset.h"
#include "json.h"
#include "strata/esdf/esdf.h"
#include "strata/map/map_config.h"

namespace strata::bench {

struct EsdfBenchSettings {
  MapConfig map;             // 5 cm voxels
  EsdfConfig esdf;           // default: exact up to 2 m
  std::size_t frames = 150;  // fused (fewer when the input has fewer)
  int full_runs = 3;         // full recomputations after the last frame (median reported)
  std::size_t query_points = 100000;
  float query_radius_m = 0.2f;   // sphere test: robot radius ...
  float query_margin_m = 0.05f;  // ... plus margin
  std::string device;
};

struct EsdfRun {
  std::string input;
  std::string device_name;
  std::vector<EsdfUpdateStats> incremental;  // one per frame, warm-up included
  std::vector<EsdfUpdateStats> full;
  std::vector<double> fusion_device_ms;  // normals + allocate + integrate per frame
  std::uint32_t blocks = 0;
  std::size_t known_voxels = 0;
  double reference_ms = 0.0;  // computeEsdfReference on the downloaded map (steady_clock)
  Json agreement;             // device ESDF against the reference
  Json queries;               // host and device query throughput and agreement
  Json slice;                 // slice picture time and size
  bool ok = true;             // every self-check passed
};

/// Runs everything on a fresh Vulkan context. Progress to stderr.
EsdfRun runEsdfBench(const std::string& input, const Dataset& data,
                     const EsdfBenchSettings& settings);

/// The report of one run.
Json esdfRunReport(const EsdfRun& run);

}  // namespace strata::bench
