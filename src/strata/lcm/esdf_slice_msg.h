#pragma once
// esdf_slice_t from the host ESDF: the voxel layer holding height z over the bounding box of the
// blocks that reach it. Raw distances (planners), not a picture (apps/esdf_slice.h draws those).
#include <cstdint>

#include "strata/map/esdf_layer.h"
#include "strata/esdf_slice_t.hpp"

namespace strata::lcm_io {

/// State values of esdf_slice_t.state.
inline constexpr std::int8_t kSliceOutside = 0;
inline constexpr std::int8_t kSliceUnknown = 1;
inline constexpr std::int8_t kSliceObserved = 2;

/// An empty slice (width = height = 0) when no block holds z.
esdf_slice_t makeEsdfSlice(const EsdfMap& esdf, float z_m, std::int64_t utime);

}  // namespace strata::lcm_io
