#pragma once
// What skipped keyframes saw change: free space through vacated places and the surfaces of
// arrived objects, integrated into a session's change-detection layer without fusing the images.
//
// The selection's raycast has compared each keyframe's depth with the map on its sample grid. A
// vacated sample looks beyond the map's surface (something left); an arrived sample measures a
// surface in front of the map's, or where its ray meets none (something arrived). Vacated samples
// are seeds: the place is what the last observations (`place`, the change layers' map) hold
// around them, and the keyframe's full-resolution depth is kept, and tested pixel by pixel, where
// that place can project (keepDepthAround).
//
// Vacated places, per view (one skipped keyframe) and per voxel, at most once per view: the voxel
// lies within place_radius_m of one of the view's vacated samples (the map's surface point on its
// ray) and holds something in `place` (weight > 0 and tsdf below the truncation distance: a
// surface or an object's inside, as last observed). It then takes the update fusing the keyframe
// would give it (integrateVoxelReference, with the normals of the kept depth and no colour): a
// free observation where its pixel measures at least the truncation distance beyond it, the
// surface's distance where it measures the surface, nothing where the pixel's depth was not kept
// or the voxel lies more than the truncation distance behind what it measures. Surface
// observations are integrated with the free ones so that static surfaces of the place seen at a
// grazing angle or across a depth edge are not worn away. Free space where nothing was last
// observed is left out: no earlier instance can stand there, and it would only allocate. A place
// thus turns free in the static map only where min_weight views saw through it.
//
// Arrivals, per view and per voxel, at most once per view: an arrived surface lies where its
// samples measure it, so the kept depth is each arrived sample's cell and arrived_ring_cells
// around it; the voxels within reach of that square (and the truncation band) take the same whole
// update, unless it is free space where nothing was held or last observed.
//
// Lengths in metres, image coordinates in pixels; poses T_W_C take camera to world coordinates,
// points are in the world frame. Thread safe (pure functions).
#include <Eigen/Geometry>
#include <cstddef>
#include <cstdint>
#include <unordered_map>
#include <unordered_set>
#include <vector>

#include "strata/core/types.h"
#include "strata/map/tsdf_map.h"

namespace strata::change {

/// One sample of a keyframe that looks beyond the map's surface: something left.
struct VacatedSample {
  int u_px = 0;
  int v_px = 0;
  float surface_m = 0.0f;  // the map's surface there (rendered depth, camera z)
};

/// A keyframe's depth image, kept only in square tiles of tile_px aligned to pixel (0, 0) (with
/// a sample grid of stride tile_px and offset tile_px / 2, a tile is a sample's cell).
class DepthTiles {
 public:
  explicit DepthTiles(int tile_px = 10);
  /// Copies the tiles of `depth` that hold a pixel of [u_lo, u_hi) x [v_lo, v_hi), once each.
  void keep(const DepthImage& depth, int u_lo, int u_hi, int v_lo, int v_hi);
  /// The depth at pixel (u, v); NaN where no tile is kept (or outside the image).
  float at(int u, int v) const;
  std::size_t tileCount() const { return tiles_.size(); }
  std::size_t pixelCount() const { return tiles_.size() * tile_px_ * tile_px_; }
  int tilePx() const { return tile_px_; }
  /// A width x height depth image with the kept tiles and NaN (no depth) elsewhere.
  DepthImage image(int width_px, int height_px) const;

 private:
  static std::uint64_t key(int tx, int ty);
  int tile_px_;
  std::unordered_map<std::uint64_t, std::vector<float>> tiles_;
};

/// One sample of a keyframe that measures a surface in front of the map's (or where the map has
/// none along its ray): something arrived there.
struct ArrivedSample {
  int u_px = 0;
  int v_px = 0;
  float measured_m = 0.0f;  // the keyframe's depth there (camera z)
};

/// A keyframe's vacated and arrived samples, its depth around them and its pose.
struct ChangedView {
  Eigen::Isometry3f T_W_C = Eigen::Isometry3f::Identity();
  std::vector<VacatedSample> samples;
  DepthTiles depth;
  std::vector<ArrivedSample> arrived;
};

struct FreeSpaceConfig {
  /// Side of a sample's cell (the sample grid's stride) and of the kept depth's tiles.
  int cell_px = 10;
  /// Radius of the place around each vacated sample, metres, in (0, 2]: about an office chair's
  /// half size.
  float place_radius_m = 0.3f;
  /// Cells kept around an arrived sample's own, on each side: an arrived surface lies where its
  /// samples measure it, so the cells between neighbouring samples cover it (0: arrivals off).
  int arrived_ring_cells = 1;

  void validate() const;  // InputError naming the field
};

/// Global voxel indices (the same type as block indices, so the map's block hash serves).
using VoxelSet = std::unordered_set<GlobalVoxelIndex, BlockIndexHash>;

struct FreeSpaceStats {
  std::size_t views = 0;            // views given
  std::size_t samples = 0;          // their vacated samples
  std::size_t voxels = 0;           // voxel observations added, free or surface (once per view)
  std::size_t free_voxels = 0;      // ... of them free (the pixel measures truncation beyond)
  std::size_t arrived_samples = 0;  // the views' arrived samples (0 with arrived_ring_cells 0)
  std::size_t depth_pixels = 0;     // pixels of depth kept with the views
};

/// The view's vacated samples as world points on the map's surface (those with a non-finite or
/// non-positive surface depth left out).
std::vector<Eigen::Vector3f> samplePoints(const ChangedView& view, const CameraIntrinsics& k);

/// Keeps in view.depth (tiles of config.cell_px) the depth of `depth` where the place around
/// each of view.samples can project: the square around its pixel of half side
/// fx * place_radius_m / (surface_m - place_radius_m), the sphere's image seen from its nearest
/// depth (0.1 m at least).
void keepDepthAround(const DepthImage& depth, const CameraIntrinsics& intrinsics,
                     const FreeSpaceConfig& config, ChangedView& view);

/// Integrates what `views` saw change into `session` (see the rules above); `intrinsics`: the
/// keyframes' camera; `place`: the last observations, on session's grid (InputError otherwise).
/// Voxels updated are added to *updated when non-null, and to *own those whose observation puts
/// them on the other side of a surface than `place` does (free where it holds an inside, inside
/// where it holds free space or nothing): the session's own evidence against the last
/// observations, which carry_forward.h does not carry into. A voxel whose observation agrees with
/// the last one is not own evidence and may still be carried. Blocks are allocated in `session`
/// where a voxel is updated.
FreeSpaceStats integrateChangedPlaces(const std::vector<ChangedView>& views,
                                      const CameraIntrinsics& intrinsics,
                                      const FreeSpaceConfig& config, const TsdfMap& place,
                                      TsdfMap& session, VoxelSet* updated = nullptr,
                                      VoxelSet* own = nullptr);

}  // namespace strata::change
