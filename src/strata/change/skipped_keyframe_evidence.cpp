#include "strata/change/skipped_keyframe_evidence.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "strata/core/error.h"
#include "strata/map/camera_math.h"
#include "strata/integrate/normal_estimation.h"
#include "strata/integrate/tsdf_integration.h"

namespace strata::change {

void FreeSpaceConfig::validate() const {
  if (cell_px < 1) {
    throw InputError("free space cell_px must be >= 1, got " + std::to_string(cell_px));
  }
  // Beyond a few metres the place is no longer one object's, and the kept depth grows with it.
  if (!(place_radius_m > 0.0f) || !(place_radius_m <= 2.0f)) {
    throw InputError("free space place_radius_m must be in (0, 2] m, got " +
                     std::to_string(place_radius_m));
  }
  if (arrived_ring_cells < 0 || arrived_ring_cells > 8) {
    throw InputError("free space arrived_ring_cells must be in [0, 8], got " +
                     std::to_string(arrived_ring_cells));
  }
}

DepthTiles::DepthTiles(int tile_px) : tile_px_(tile_px) {
  if (tile_px < 1)
    throw InputError("depth tiles need tile_px >= 1, got " + std::to_string(tile_px));
}

std::uint64_t DepthTiles::key(int tx, int ty) {
  return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(ty)) << 32) |
         static_cast<std::uint32_t>(tx);
}

void DepthTiles::keep(const DepthImage& depth, int u_lo, int u_hi, int v_lo, int v_hi) {
  u_lo = std::max(u_lo, 0);
  v_lo = std::max(v_lo, 0);
  u_hi = std::min(u_hi, depth.width_px);
  v_hi = std::min(v_hi, depth.height_px);
  if (u_lo >= u_hi || v_lo >= v_hi) return;
  for (int ty = v_lo / tile_px_; ty <= (v_hi - 1) / tile_px_; ++ty) {
    for (int tx = u_lo / tile_px_; tx <= (u_hi - 1) / tile_px_; ++tx) {
      std::vector<float>& tile = tiles_[key(tx, ty)];
      if (!tile.empty()) continue;
      tile.assign(static_cast<std::size_t>(tile_px_) * tile_px_, NAN);
      for (int y = 0; y < tile_px_; ++y) {
        const int v = ty * tile_px_ + y;
        if (v >= depth.height_px) break;
        for (int x = 0; x < tile_px_; ++x) {
          const int u = tx * tile_px_ + x;
          if (u >= depth.width_px) break;
          tile[static_cast<std::size_t>(y) * tile_px_ + x] = depth.at(u, v);
        }
      }
    }
  }
}

float DepthTiles::at(int u, int v) const {
  if (u < 0 || v < 0) return NAN;
  const auto it = tiles_.find(key(u / tile_px_, v / tile_px_));
  if (it == tiles_.end()) return NAN;
  return it->second[static_cast<std::size_t>(v % tile_px_) * tile_px_ + u % tile_px_];
}

DepthImage DepthTiles::image(int width_px, int height_px) const {
  DepthImage out(width_px, height_px, NAN);
  for (const auto& [key, tile] : tiles_) {
    const int tx = static_cast<int>(static_cast<std::uint32_t>(key & 0xFFFFFFFFu));
    const int ty = static_cast<int>(static_cast<std::uint32_t>(key >> 32));
    for (int y = 0; y < tile_px_; ++y) {
      const int v = ty * tile_px_ + y;
      if (v < 0 || v >= height_px) continue;
      for (int x = 0; x < tile_px_; ++x) {
        const int u = tx * tile_px_ + x;
        if (u >= 0 && u < width_px) out.at(u, v) = tile[static_cast<std::size_t>(y) * tile_px_ + x];
      }
    }
  }
  return out;
}

std::vector<Eigen::Vector3f> samplePoints(const ChangedView& view, const CameraIntrinsics& k) {
  const Eigen::Vector4f K(k.fx_px, k.fy_px, k.cx_px, k.cy_px);
  std::vector<Eigen::Vector3f> points_W;
  for (const VacatedSample& s : view.samples) {
    if (!(s.surface_m > 0.0f) || !std::isfinite(s.surface_m)) continue;
    const Eigen::Vector3f ray_C =
        pixelRay(static_cast<float>(s.u_px), static_cast<float>(s.v_px), K);
    points_W.push_back(view.T_W_C * Eigen::Vector3f(ray_C * s.surface_m));
  }
  return points_W;
}

namespace {

/// For each block of `place` that holds a voxel within radius_m of a point: those points.
std::unordered_map<BlockIndex, std::vector<Eigen::Vector3f>, BlockIndexHash> blocksNear(
    const std::vector<Eigen::Vector3f>& points_W, const TsdfMap& place, float radius_m) {
  const float block_m = place.config().voxel_size_m * kBlockEdge;
  std::unordered_map<BlockIndex, std::vector<Eigen::Vector3f>, BlockIndexHash> near;
  for (const Eigen::Vector3f& p : points_W) {
    const Eigen::Vector3i lo = ((p.array() - radius_m) / block_m).floor().cast<int>();
    const Eigen::Vector3i hi = ((p.array() + radius_m) / block_m).floor().cast<int>();
    for (int z = lo.z(); z <= hi.z(); ++z) {
      for (int y = lo.y(); y <= hi.y(); ++y) {
        for (int x = lo.x(); x <= hi.x(); ++x) {
          const BlockIndex b(x, y, z);
          if (place.findBlock(b) != nullptr) near[b].push_back(p);
        }
      }
    }
  }
  return near;
}

/// The voxels of `place` that hold something (weight > 0, tsdf below truncation) within radius_m
/// of a point.
VoxelSet placeVoxels(const std::vector<Eigen::Vector3f>& points_W, const TsdfMap& place,
                     float radius_m) {
  const float voxel_m = place.config().voxel_size_m;
  const float truncation_m = place.config().truncationDistance();
  const float radius2 = radius_m * radius_m;
  VoxelSet out;
  for (const auto& [b, near_W] : blocksNear(points_W, place, radius_m)) {
    const TsdfBlock& block = *place.findBlock(b);
    for (int i = 0; i < kVoxelsPerBlock; ++i) {
      const TsdfVoxel& last = block[i];
      if (!(last.weight > 0.0f) || !(last.tsdf_m < truncation_m)) continue;
      const GlobalVoxelIndex v =
          b * kBlockEdge + Eigen::Vector3i(i % kBlockEdge, (i / kBlockEdge) % kBlockEdge,
                                           i / (kBlockEdge * kBlockEdge));
      const Eigen::Vector3f centre_W = voxelCenter(v, voxel_m);
      const bool in_place = std::any_of(near_W.begin(), near_W.end(), [&](const auto& p) {
        return (p - centre_W).squaredNorm() <= radius2;
      });
      if (in_place) out.insert(v);
    }
  }
  return out;
}

/// The voxels within reach of the view's arrived samples' kept cells: in a ball around each
/// measured point as wide as the kept square at its depth (its diagonal) plus the truncation band,
/// those that the kept `depth` updates (a valid pixel, not more than the truncation distance
/// behind what it measures).
VoxelSet arrivedVoxels(const ChangedView& view, const CameraIntrinsics& k,
                       const FreeSpaceConfig& config, const MapConfig& map, const DepthImage& depth,
                       const std::vector<Eigen::Vector4f>& normals_C, const FrameCamera& camera) {
  VoxelSet out;
  if (config.arrived_ring_cells == 0) return out;
  const Eigen::Vector4f K(k.fx_px, k.fy_px, k.cx_px, k.cy_px);
  const float voxel_m = map.voxel_size_m;
  const float half_px = config.cell_px * (config.arrived_ring_cells + 0.5f);
  for (const ArrivedSample& s : view.arrived) {
    if (!(s.measured_m > 0.0f) || !std::isfinite(s.measured_m)) continue;
    const Eigen::Vector3f ray_C =
        pixelRay(static_cast<float>(s.u_px), static_cast<float>(s.v_px), K);
    const Eigen::Vector3f p_vox = view.T_W_C * Eigen::Vector3f(ray_C * s.measured_m) / voxel_m;
    const float radius_vox =
        (std::sqrt(2.0f) * half_px * s.measured_m / k.fx_px + map.truncationDistance()) / voxel_m;
    const Eigen::Vector3i lo = (p_vox.array() - radius_vox).floor().cast<int>();
    const Eigen::Vector3i hi = (p_vox.array() + radius_vox).floor().cast<int>();
    for (int z = lo.z(); z <= hi.z(); ++z) {
      for (int y = lo.y(); y <= hi.y(); ++y) {
        for (int x = lo.x(); x <= hi.x(); ++x) {
          const Eigen::Vector3f c = Eigen::Vector3f(x, y, z).array() + 0.5f;
          if ((c - p_vox).squaredNorm() > radius_vox * radius_vox) continue;
          const GlobalVoxelIndex v(x, y, z);
          if (out.count(v) > 0) continue;
          const VoxelObservation o =
              observeVoxelReference(voxelCenter(v, voxel_m), depth, &normals_C, camera, map);
          if (o.weight > 0.0f) out.insert(v);
        }
      }
    }
  }
  return out;
}

}  // namespace

void keepDepthAround(const DepthImage& depth, const CameraIntrinsics& intrinsics,
                     const FreeSpaceConfig& config, ChangedView& view) {
  config.validate();
  for (const VacatedSample& s : view.samples) {
    if (!std::isfinite(s.surface_m)) continue;
    const float nearest_m = std::max(s.surface_m - config.place_radius_m, 0.1f);
    const float half = std::ceil(intrinsics.fx_px * config.place_radius_m / nearest_m);
    const int half_px = static_cast<int>(std::min(half, static_cast<float>(depth.width_px)));
    view.depth.keep(depth, s.u_px - half_px, s.u_px + half_px + 1, s.v_px - half_px,
                    s.v_px + half_px + 1);
  }
  if (config.arrived_ring_cells == 0) return;
  // The sample's cell (the sample at its centre) and the ring around it.
  const int half_px = config.cell_px / 2 + config.arrived_ring_cells * config.cell_px;
  for (const ArrivedSample& s : view.arrived) {
    view.depth.keep(depth, s.u_px - half_px, s.u_px + half_px + 1, s.v_px - half_px,
                    s.v_px + half_px + 1);
  }
}

FreeSpaceStats integrateChangedPlaces(const std::vector<ChangedView>& views,
                                      const CameraIntrinsics& k, const FreeSpaceConfig& config,
                                      const TsdfMap& place, TsdfMap& session, VoxelSet* updated,
                                      VoxelSet* own) {
  config.validate();
  k.validate();
  const MapConfig& map = session.config();
  if (place.config().voxel_size_m != map.voxel_size_m) {
    throw InputError("integrateChangedPlaces: the place map's voxels (" +
                     std::to_string(place.config().voxel_size_m) +
                     " m) differ from the session layer's (" + std::to_string(map.voxel_size_m) +
                     " m)");
  }
  const float voxel_m = map.voxel_size_m;
  const float truncation_m = map.truncationDistance();  // place voxels: below it
  FreeSpaceStats stats;
  stats.views = views.size();
  for (const ChangedView& view : views) {
    if (!view.T_W_C.matrix().allFinite()) {
      throw InputError("integrateChangedPlaces: a view's pose is not finite");
    }
    stats.samples += view.samples.size();
    stats.depth_pixels += view.depth.pixelCount();
    const DepthImage depth = view.depth.image(k.width_px, k.height_px);
    const FrameCamera camera = FrameCamera::from(k, view.T_W_C.cast<double>());
    const std::vector<Eigen::Vector4f> normals_C = estimateNormalsReference(depth, camera, map);
    VoxelSet candidates = placeVoxels(samplePoints(view, k), place, config.place_radius_m);
    const VoxelSet arrived = arrivedVoxels(view, k, config, map, depth, normals_C, camera);
    if (config.arrived_ring_cells > 0) stats.arrived_samples += view.arrived.size();
    candidates.insert(arrived.begin(), arrived.end());
    // Each voxel once per view: one observation per voxel and view, as fusing the keyframe would
    // give.
    for (const GlobalVoxelIndex& v : candidates) {
      const Eigen::Vector3f centre_W = voxelCenter(v, voxel_m);
      // This view's observation alone, to compare with the last one before blending it.
      const VoxelObservation observation =
          observeVoxelReference(centre_W, depth, &normals_C, camera, map);
      if (!(observation.weight > 0.0f)) continue;
      const bool free = observation.ray_sdf_m >= truncation_m;
      const TsdfVoxel* existing = session.findVoxel(v);
      const TsdfVoxel* last = place.findVoxel(v);
      const bool last_held = last != nullptr && last->weight > 0.0f;
      // Free space where nothing stood and nothing is held yet would only allocate (a voxel of
      // an allocated block may hold nothing).
      const bool held = existing != nullptr && existing->weight > 0.0f;
      if (free && !held && !(last_held && last->tsdf_m < truncation_m)) continue;
      TsdfVoxel voxel = existing != nullptr ? *existing : TsdfVoxel{};
      applyObservation(voxel, observation, nullptr, map);
      session.allocateVoxel(v) = voxel;
      ++stats.voxels;
      stats.free_voxels += free ? 1 : 0;
      if (updated != nullptr) updated->insert(v);
      // Own evidence: the observation puts the voxel on the other side of a surface than the last
      // one did (free where something stood, inside something where nothing stood).
      const bool inside_last = last_held && last->tsdf_m < 0.0f;
      if (own != nullptr && (observation.tsdf_m < 0.0f) != inside_last) own->insert(v);
    }
  }
  return stats;
}

}  // namespace strata::change
