#pragma once
// What skipped keyframes saw change: free space through vacated places and the surfaces of
// arrived objects.
// When an object leaves, the keyframes that look through its old place measure beyond the map's
// surface there. The change detector turns that place free in the static map only from
// min_weight fused frames on; selection fuses few of those keyframes (a removed chair changes
// few samples), so the object's earlier instances stay unsegmented. The selection's raycast has
// already compared every keyframe's depth with the map on its sample grid: where a sample looks
// beyond the surface, the keyframe saw free space around that surface. This step integrates that
// free space into the session's change-detection layer, one observation per keyframe, as fusing
// the keyframe would there, but only around its vacated samples, so a place turns free only where
// min_weight keyframes saw through it.
//
// The place, not only the samples: a removed thin object (a chair) gives few vacated samples;
// most rays through its place miss it in the selection map (5 cm voxels keep little of a chair's
// thin parts; an explanation, not measured). Office, session 3: the four skipped keyframes that
// saw through a removed chair's place had 10, 3, 2 and 7 vacated samples on it; their depth
// showed 571, 380, 277 and 605 of the 699 surface voxels free that a look at the samples' own
// 10 px cells (and one cell around) had left unobserved. The vacated samples are therefore seeds:
// the place is what the last observations (the change layers' finer map) hold around them, and
// the keyframe's full-resolution depth is kept, and tested pixel by pixel, where that place can
// project.
//
// Rule, per view (one skipped keyframe) and per voxel, at most once per view: the voxel lies
// within place_radius_m of one of the view's vacated samples (the map's surface point on its ray)
// and holds something in `place` (weight > 0 and tsdf below the truncation distance: a surface or
// an object's inside, as last observed). It then takes the update fusing the keyframe would give
// it (integrateVoxelReference, with the normals of the kept depth and no colour): a free
// observation where its pixel measures at least the truncation distance beyond it, the surface's
// distance where it measures the surface, nothing where the pixel's depth was not kept or the
// voxel lies more than the truncation distance behind what it measures. The surface observations
// matter as much as the free ones: free space alone would wear away every static surface of the
// place seen at a grazing angle or across a depth edge (office, 240 keyframes per session: 2 false
// segments of 39). Free space where nothing was last observed is left out: no earlier instance
// can stand there, and it would only allocate.
//
// Arrivals, the other half: an object that arrives is selected for only where it changes a
// keyframe's score enough, and a small one does not (office, 120 keyframes per session: an
// archive box moved in session 2 was seen by 12 keyframes, 2 of them fused; never found). A
// sample that measures a surface in front of the map's (or where its ray meets none) is an
// arrived sample; its surface lies where it measures it, so the kept depth is its cell and
// arrived_ring_cells around, and the voxels within reach of that square (and the truncation band)
// take the same whole update, once per view, unless it is free space where nothing was held or
// last observed. Office, 120 keyframes: every instance 25 of 31 and arrivals 9 of 11, equal to
// fusing every keyframe, reading 25.9 % of the skipped keyframes' depth pixels (without arrivals,
// free observations counted as own evidence: 23 and 8, reading 19.6 %).
// Thread safe (pure functions).
#include <Eigen/Geometry>
#include <cstddef>
#include <cstdint>
#include <unordered_map>
#include <unordered_set>
#include <vector>

#include "core/types.h"
#include "map/tsdf_map.h"

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
  /// Radius of the place around each vacated sample: about an office chair's half size. Office,
  /// 60 keyframes per session (free observations only, carry-forward radius 0.75 spacings):
  /// 0.3 m finds 20 of 25 instances reading 17 % of the skipped keyframes' depth pixels; 0.5 m
  /// the same 20 with 31 %.
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
/// the last one may be carried (office, 120 keyframes per session: counting every place voxel that
/// took an observation as own evidence kept the printer, standing as before beside a place vacated
/// a session earlier, from being carried forward; lost in session 4). Blocks are allocated in
/// `session` where a voxel is updated.
FreeSpaceStats integrateChangedPlaces(const std::vector<ChangedView>& views,
                                      const CameraIntrinsics& intrinsics,
                                      const FreeSpaceConfig& config, const TsdfMap& place,
                                      TsdfMap& session, VoxelSet* updated = nullptr,
                                      VoxelSet* own = nullptr);

}  // namespace strata::change
