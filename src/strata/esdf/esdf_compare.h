#pragma once
// How a computed ESDF agrees with another (the device's with the C++ reference, an incremental
// update with a full one): the tolerance every check of the ESDF uses.
// Thread safety: all functions are thread safe (they only read the maps).
#include <cstddef>

#include "strata/esdf/esdf.h"

namespace strata {

/// The ESDF's tolerance: at most this share of the compared voxels may differ by more than one
/// voxel size ...
inline constexpr double kEsdfMaxShareOverVoxel = 0.002;
/// ... and the mean absolute difference must stay below this many voxel sizes.
inline constexpr double kEsdfMaxMeanErrorVoxels = 0.1;

/// Agreement on the voxels the reference observes with a site within its maximum distance.
struct EsdfAgreement {
  std::size_t compared = 0;
  std::size_t over_voxel = 0;  // |difference| above one voxel size
  double mean_abs_voxels = 0.0;
  /// Within the tolerance above (an empty comparison passes).
  bool ok() const;
};

/// Compares `esdf` with `reference` voxel by voxel (a block `esdf` lacks counts as distance 0).
EsdfAgreement compareEsdfWithReference(const EsdfMap& esdf, const EsdfMap& reference);

}  // namespace strata
