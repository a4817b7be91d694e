#pragma once
// A horizontal slice of the ESDF as a picture: signed distance colour-mapped with a perceptual ramp
// (dark purple at the lowest distance through teal to yellow at the colour range's top), unknown
// voxels hatched grey, unallocated space flat light grey, a colour bar with tick labels, a legend
// and a title line (built-in 5x7 font). x runs right, y up; one voxel is a square of pixels.
#include <Eigen/Core>
#include <cstddef>
#include <string>

#include "cli/esdf_slice_font.h"
#include "strata/core/types.h"
#include "strata/map/esdf_layer.h"

namespace strata::apps {

struct EsdfSliceOptions {
  /// Height of the slice (world z), metres; the voxel layer holding it is drawn.
  float z_m = 1.0f;
  /// Cap of the colour range, metres (positive, finite): the range runs from min(0, the slice's
  /// lowest distance) to the slice's highest rounded up to a tick, at most this.
  float max_distance_m = 2.0f;
  /// Voxels are drawn as squares of a whole number of pixels (1 to 16), chosen so the map is at
  /// least this many pixels on its longer side: small maps stay readable, big ones stay 1:1.
  int min_map_px = 480;
  /// Title line; "" writes "ESDF AT Z=... M (VOXEL ... M), SIGNED DISTANCE IN M".
  std::string title;
};

struct EsdfSliceStats {
  int width_voxels = 0;  // the slice grid: bounding box of the blocks at z
  int height_voxels = 0;
  int pixels_per_voxel = 1;
  std::size_t known = 0;        // observed voxels
  std::size_t unknown = 0;      // allocated, never observed
  std::size_t outside = 0;      // in the box but in no allocated block
  float min_distance_m = 0.0f;  // over known voxels (0 when there are none)
  float max_distance_m = 0.0f;
  float colour_min_m = 0.0f;  // the colour range (see EsdfSliceOptions::max_distance_m)
  float colour_max_m = 0.0f;
  // Where the map lies in the picture, for drawing over it: the pixel of the map's top-left
  // corner, and the global voxel index (x, y) of the grid's lower-left voxel.
  int map_x_px = 0;
  int map_y_px = 0;
  int grid_x0_voxels = 0;
  int grid_y0_voxels = 0;
};

/// The picture's pixel (x right, y down; fractional) of world point (x, y) on a slice.
Eigen::Vector2f slicePixel(const EsdfSliceStats& stats, float voxel_size_m, float x_m, float y_m);

struct EsdfSlice {
  ColorImage image;
  EsdfSliceStats stats;
};

/// Throws InputError when options are invalid or no block of the map holds z (naming the z range
/// the map covers).
EsdfSlice renderEsdfSlice(const EsdfMap& map, const EsdfSliceOptions& options);

/// Renders and writes a PNG. Throws like renderEsdfSlice, and Error when the file cannot be
/// written.
EsdfSliceStats writeEsdfSlicePng(const std::string& path, const EsdfMap& map,
                                 const EsdfSliceOptions& options);

/// The perceptual ramp (viridis-like), t clamped to [0, 1].
Rgb esdfColour(float t);

/// Colours of the areas that carry no distance.
inline constexpr Rgb kUnknownHatch[2] = {{{150, 150, 150}}, {{105, 105, 105}}};
inline constexpr Rgb kNoBlockColour = {{215, 215, 215}};

}  // namespace strata::apps
