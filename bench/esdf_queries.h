#pragma once
// Planner-query throughput for `strata-bench esdf`: host EsdfQuery and device EsdfQueryKernel on
// the same points (half near observed voxels, half anywhere in the map's box), their agreement,
// and the time to render a slice picture.
#include "json.h"
#include "strata/esdf/esdf.h"
#include "strata/vk/vk.h"

namespace strata::bench {

struct EsdfBenchSettings;

/// {"points", "host": {...}, "device": {...}, "agreement": {...}}; clears `ok` when device and host
/// disagree beyond float rounding.
Json benchQueries(vk::Context& context, DeviceEsdf& esdf, const EsdfMap& map,
                  const EsdfBenchSettings& settings, bool& ok);

/// Renders (not writes) the slice through the layer with the most blocks: {"z_m", "ms", ...}.
Json benchSlice(const EsdfMap& map);

}  // namespace strata::bench
