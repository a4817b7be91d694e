#include "change/carry_free.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "core/error.h"
#include "kernels/camera_math.h"

namespace strata::change {

void FreeSpaceConfig::validate() const {
  if (!(cell_px >= 1.0f) || !std::isfinite(cell_px)) {
    throw InputError("free space cell_px must be a number >= 1, got " + std::to_string(cell_px));
  }
  if (!(band_m > 0.0f) || !std::isfinite(band_m)) {
    throw InputError("free space band_m must be a positive number, got " + std::to_string(band_m));
  }
}

namespace {

struct Cell {
  float u_lo, u_hi, v_lo, v_hi;  // pixels
  float z_lo, z_hi;              // camera z, metres
};

/// The voxels whose centres lie in `cell` (its frustum slice), visited once each.
template <typename Visit>
void forEachVoxelInCell(const Cell& cell, const Eigen::Isometry3f& T_W_C,
                        const Eigen::Isometry3f& T_C_W, const CameraIntrinsics& k, float voxel_m,
                        Visit&& visit) {
  const Eigen::Vector4f K(k.fx_px, k.fy_px, k.cx_px, k.cy_px);
  Eigen::Vector3f lo = Eigen::Vector3f::Constant(INFINITY);
  Eigen::Vector3f hi = Eigen::Vector3f::Constant(-INFINITY);
  for (const float z : {cell.z_lo, cell.z_hi}) {
    for (const float u : {cell.u_lo, cell.u_hi}) {
      for (const float v : {cell.v_lo, cell.v_hi}) {
        const Eigen::Vector3f p_W = T_W_C * Eigen::Vector3f(pixelRay(u, v, K) * z);
        lo = lo.cwiseMin(p_W);
        hi = hi.cwiseMax(p_W);
      }
    }
  }
  const Eigen::Vector3i first = (lo / voxel_m).array().floor().cast<int>();
  const Eigen::Vector3i last = (hi / voxel_m).array().floor().cast<int>();
  for (int z = first.z(); z <= last.z(); ++z) {
    for (int y = first.y(); y <= last.y(); ++y) {
      for (int x = first.x(); x <= last.x(); ++x) {
        const GlobalVoxelIndex v(x, y, z);
        const Eigen::Vector3f centre_C = T_C_W * voxelCenter(v, voxel_m);
        const float depth = centre_C.z();
        if (!(depth >= cell.z_lo && depth <= cell.z_hi)) continue;
        const float u = k.fx_px * centre_C.x() / depth + k.cx_px;
        const float pv = k.fy_px * centre_C.y() / depth + k.cy_px;
        if (u < cell.u_lo || u > cell.u_hi || pv < cell.v_lo || pv > cell.v_hi) continue;
        visit(v);
      }
    }
  }
}

}  // namespace

FreeSpaceStats integrateFreeSpace(const std::vector<VacatedView>& views,
                                  const CameraIntrinsics& intrinsics, const FreeSpaceConfig& config,
                                  TsdfMap& session, VoxelSet* updated) {
  config.validate();
  intrinsics.validate();
  const MapConfig& map = session.config();
  const float voxel_m = map.voxel_size_m;
  const float truncation_m = map.truncationDistance();
  const float half_cell = 0.5f * config.cell_px;
  FreeSpaceStats stats;
  stats.views = views.size();
  for (const VacatedView& view : views) {
    if (!view.T_W_C.matrix().allFinite()) {
      throw InputError("integrateFreeSpace: a view's pose is not finite");
    }
    const Eigen::Isometry3f T_C_W = view.T_W_C.inverse();
    VoxelSet in_view;  // one observation per voxel and view, as fusing the keyframe would give
    for (const VacatedSample& s : view.samples) {
      ++stats.samples;
      Cell cell{s.u_px - half_cell,
                s.u_px + half_cell,
                s.v_px - half_cell,
                s.v_px + half_cell,
                std::max(s.surface_m - config.band_m, map.min_depth_m),
                std::min(s.surface_m + config.band_m, s.measured_m - truncation_m)};
      // Non-finite numbers fail these comparisons and are skipped with the empty cells.
      if (!(cell.z_lo < cell.z_hi) || !(s.measured_m <= map.max_depth_m)) continue;
      if (!std::isfinite(s.u_px) || !std::isfinite(s.v_px)) continue;
      forEachVoxelInCell(
          cell, view.T_W_C, T_C_W, intrinsics, voxel_m, [&](const GlobalVoxelIndex& v) {
            if (!in_view.insert(v).second) return;
            TsdfVoxel& voxel = session.allocateVoxel(v);
            voxel.tsdf_m = (voxel.tsdf_m * voxel.weight + truncation_m) / (voxel.weight + 1.0f);
            voxel.weight = std::min(voxel.weight + 1.0f, map.max_weight);
            ++stats.voxels;
            if (updated != nullptr) updated->insert(v);
          });
    }
  }
  return stats;
}

}  // namespace strata::change
