#pragma once
// The map `strata-bench plan` plans on: a shipped world's first session as a TSDF of the exact
// signed distance (WorldScene::signedDistance at every voxel centre of the blocks covering the
// world's bounds; observed wherever it lies in front of or within the truncation band, as a
// session that saw every surface would leave it), and its exact ESDF (computeEsdfReference).
// NOTE: from truth rather than fused depth so the comparison of planners does not depend on which
// corners a simulated camera path happened to see; unknown space then lies only deep inside solids.
#include <string>

#include "strata/map/esdf_layer.h"
#include "strata/map/tsdf_map.h"

namespace strata::bench {

struct WorldMap {
  TsdfMap tsdf{MapConfig{}};
  EsdfMap esdf;
  double tsdf_ms = 0.0;  // signed distances of every voxel (all host threads)
  double esdf_ms = 0.0;  // computeEsdfReference
};

/// InputError when the world cannot be found or read.
WorldMap buildWorldMap(const std::string& world, float voxel_size_m, float esdf_max_distance_m);

}  // namespace strata::bench
