#include "change/carry_free.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "core/error.h"
#include "kernels/camera_math.h"
#include "kernels/normal_estimation.h"
#include "kernels/tsdf_integration.h"

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

std::vector<Eigen::Vector3f> samplePoints(const VacatedView& view, const CameraIntrinsics& k) {
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

}  // namespace

void keepDepthAround(const DepthImage& depth, const CameraIntrinsics& intrinsics,
                     const FreeSpaceConfig& config, VacatedView& view) {
  config.validate();
  for (const VacatedSample& s : view.samples) {
    if (!std::isfinite(s.surface_m)) continue;
    const float nearest_m = std::max(s.surface_m - config.place_radius_m, 0.1f);
    const float half = std::ceil(intrinsics.fx_px * config.place_radius_m / nearest_m);
    const int half_px = static_cast<int>(std::min(half, static_cast<float>(depth.width_px)));
    view.depth.keep(depth, s.u_px - half_px, s.u_px + half_px + 1, s.v_px - half_px,
                    s.v_px + half_px + 1);
  }
}

FreeSpaceStats integrateFreeSpace(const std::vector<VacatedView>& views, const CameraIntrinsics& k,
                                  const FreeSpaceConfig& config, const TsdfMap& place,
                                  TsdfMap& session, VoxelSet* updated) {
  config.validate();
  k.validate();
  const MapConfig& map = session.config();
  if (place.config().voxel_size_m != map.voxel_size_m) {
    throw InputError("integrateFreeSpace: the place map's voxels (" +
                     std::to_string(place.config().voxel_size_m) +
                     " m) differ from the session layer's (" + std::to_string(map.voxel_size_m) +
                     " m)");
  }
  const float voxel_m = map.voxel_size_m;
  const float truncation_m = map.truncationDistance();  // place voxels: below it
  const float radius2 = config.place_radius_m * config.place_radius_m;
  FreeSpaceStats stats;
  stats.views = views.size();
  for (const VacatedView& view : views) {
    if (!view.T_W_C.matrix().allFinite()) {
      throw InputError("integrateFreeSpace: a view's pose is not finite");
    }
    stats.samples += view.samples.size();
    stats.depth_pixels += view.depth.pixelCount();
    const DepthImage depth = view.depth.image(k.width_px, k.height_px);
    const FrameCamera camera = FrameCamera::from(k, view.T_W_C.cast<double>());
    const std::vector<Eigen::Vector4f> normals_C = estimateNormalsReference(depth, camera, map);
    // Each block once per view, so each voxel too: one observation per voxel and view, as fusing
    // the keyframe would give.
    for (const auto& [b, points_W] :
         blocksNear(samplePoints(view, k), place, config.place_radius_m)) {
      const TsdfBlock& block = *place.findBlock(b);
      for (int i = 0; i < kVoxelsPerBlock; ++i) {
        const TsdfVoxel& last = block[i];
        if (!(last.weight > 0.0f) || !(last.tsdf_m < truncation_m)) continue;
        const GlobalVoxelIndex v =
            b * kBlockEdge + Eigen::Vector3i(i % kBlockEdge, (i / kBlockEdge) % kBlockEdge,
                                             i / (kBlockEdge * kBlockEdge));
        const Eigen::Vector3f centre_W = voxelCenter(v, voxel_m);
        const bool in_place = std::any_of(points_W.begin(), points_W.end(), [&](const auto& p) {
          return (p - centre_W).squaredNorm() <= radius2;
        });
        if (!in_place) continue;
        const TsdfVoxel* existing = session.findVoxel(v);
        TsdfVoxel voxel = existing != nullptr ? *existing : TsdfVoxel{};
        const TsdfVoxel before = voxel;
        integrateVoxelReference(voxel, centre_W, depth, &normals_C, nullptr, camera, map);
        if (voxel.weight == before.weight && voxel.tsdf_m == before.tsdf_m) continue;
        session.allocateVoxel(v) = voxel;
        ++stats.voxels;
        if (updated != nullptr) updated->insert(v);
      }
    }
  }
  return stats;
}

}  // namespace strata::change
