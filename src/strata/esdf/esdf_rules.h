#pragma once
// The per-voxel ESDF rules shared by the reference (esdf_reference.cpp) and the device path; the
// shaders esdf_gather_sites.comp and esdf_scatter.comp apply the same rules (see their headers).
#include <cmath>
#include <cstdint>

#include "strata/map/esdf_layer.h"
#include "strata/map/tsdf_map.h"

namespace strata {

/// The maximum distance in whole voxels, as integers: a site counts when the squared distance
/// between voxel centres (in voxels^2) is at most max_d2. Computed once on the host and handed to
/// the kernels so device and reference agree exactly.
struct EsdfReach {
  int max_voxels = 0;        // floor(max_distance / voxel): no site offset component exceeds it
  std::uint32_t max_d2 = 0;  // floor((max_distance / voxel)^2)
};

inline EsdfReach esdfReach(const EsdfConfig& config, float voxel_size_m) {
  const double reach = static_cast<double>(config.max_distance_m) / voxel_size_m;
  // NOTE: a tiny epsilon so 2.0 / 0.05 reads as 40 voxels, not 39.999...
  EsdfReach r;
  r.max_voxels = static_cast<int>(std::floor(reach + 1e-6));
  r.max_d2 = static_cast<std::uint32_t>(std::floor(reach * reach + 1e-4));
  return r;
}

inline bool esdfVoxelObserved(const TsdfVoxel& voxel, const EsdfConfig& config) {
  return voxel.weight >= config.min_weight;
}

/// A site: an observed voxel on the surface (|tsdf| within the site threshold).
inline bool isEsdfSite(const TsdfVoxel& voxel, const EsdfConfig& config, float voxel_size_m) {
  return esdfVoxelObserved(voxel, config) &&
         std::fabs(voxel.tsdf_m) <= config.site_threshold_voxels * voxel_size_m;
}

/// The ESDF voxel from the voxel's own TSDF and its nearest site (`has_site` false when no site
/// lies within the reach). Distance = sign(tsdf) * |offset| * voxel (max_distance without a site);
/// unobserved voxels keep the unsigned distance and no observed flag.
inline EsdfVoxel makeEsdfVoxel(const TsdfVoxel& tsdf, bool has_site, const Eigen::Vector3i& offset,
                               const EsdfConfig& config, float voxel_size_m) {
  EsdfVoxel out;
  const bool observed = esdfVoxelObserved(tsdf, config);
  float distance_m = config.max_distance_m;
  if (has_site) {
    const auto d2 = static_cast<float>(offset.squaredNorm());
    distance_m = std::fmin(std::sqrt(d2) * voxel_size_m, config.max_distance_m);
    out.site_and_flags = kEsdfHasSiteBit | packSiteOffset(offset);
  }
  if (observed) out.site_and_flags |= kEsdfObservedBit;
  out.distance_m = observed && tsdf.tsdf_m < 0.0f ? -distance_m : distance_m;
  return out;
}

}  // namespace strata
