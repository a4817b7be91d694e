#include "cli/esdf_slice.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <sstream>
#include <vector>

#include "cli/esdf_slice_legend.h"
#include "strata/core/error.h"
#include "strata/io/image_io.h"

namespace strata::apps {
namespace {

using slice_detail::Layout;

enum class Cell : std::uint8_t { kKnown, kUnknown, kNoBlock };

/// The voxel layer at z over the bounding box of the blocks that hold it.
struct SliceGrid {
  int x0 = 0, y0 = 0;  // global voxel index of the grid's (0, 0)
  int nx = 0, ny = 0;
  std::vector<float> distance_m;
  std::vector<Cell> cells;
};

void validate(const EsdfMap& map, const EsdfSliceOptions& o) {
  if (!std::isfinite(o.z_m)) throw InputError("slice z must be finite");
  if (!std::isfinite(o.max_distance_m) || o.max_distance_m <= 0.0f) {
    throw InputError("slice --max-distance must be positive and finite");
  }
  if (!(map.voxel_size_m > 0.0f)) throw InputError("ESDF map has no valid voxel size");
}

[[noreturn]] void throwNoBlockAtZ(const EsdfMap& map, float z_m) {
  std::ostringstream msg;
  msg << "no ESDF block holds z = " << z_m << " m";
  if (map.blocks.empty()) {
    msg << ": the map is empty";
  } else {
    int lo = std::numeric_limits<int>::max(), hi = std::numeric_limits<int>::min();
    for (const auto& [b, block] : map.blocks) {
      lo = std::min(lo, b.z());
      hi = std::max(hi, b.z());
    }
    const float block_m = map.voxel_size_m * kBlockEdge;
    msg << "; the map covers z from " << lo * block_m << " to " << (hi + 1) * block_m << " m";
  }
  throw InputError(msg.str());
}

SliceGrid sliceGrid(const EsdfMap& map, float z_m) {
  const int kz = static_cast<int>(std::floor(z_m / map.voxel_size_m));
  const int bz = floorDiv(kz, kBlockEdge);
  std::vector<std::pair<BlockIndex, const EsdfBlock*>> layer;
  for (const auto& [b, block] : map.blocks) {
    if (b.z() == bz) layer.emplace_back(b, &block);
  }
  if (layer.empty()) throwNoBlockAtZ(map, z_m);
  Eigen::Vector2i lo = Eigen::Vector2i::Constant(std::numeric_limits<int>::max());
  Eigen::Vector2i hi = Eigen::Vector2i::Constant(std::numeric_limits<int>::min());
  for (const auto& [b, block] : layer) {
    lo = lo.cwiseMin(b.head<2>());
    hi = hi.cwiseMax(b.head<2>());
  }
  SliceGrid g;
  g.x0 = lo.x() * kBlockEdge;
  g.y0 = lo.y() * kBlockEdge;
  g.nx = (hi.x() - lo.x() + 1) * kBlockEdge;
  g.ny = (hi.y() - lo.y() + 1) * kBlockEdge;
  g.distance_m.assign(static_cast<std::size_t>(g.nx) * g.ny, 0.0f);
  g.cells.assign(g.distance_m.size(), Cell::kNoBlock);
  const int local_z = kz - bz * kBlockEdge;
  for (const auto& [b, block] : layer) {
    for (int y = 0; y < kBlockEdge; ++y) {
      for (int x = 0; x < kBlockEdge; ++x) {
        const EsdfVoxel& v = (*block)[linearVoxelIndex(x, y, local_z)];
        const std::size_t i = static_cast<std::size_t>(b.y() * kBlockEdge + y - g.y0) * g.nx +
                              (b.x() * kBlockEdge + x - g.x0);
        g.cells[i] = esdfObserved(v) ? Cell::kKnown : Cell::kUnknown;
        g.distance_m[i] = v.distance_m;
      }
    }
  }
  return g;
}

EsdfSliceStats gridStats(const SliceGrid& g, float max_distance_m) {
  EsdfSliceStats s;
  s.width_voxels = g.nx;
  s.height_voxels = g.ny;
  s.min_distance_m = std::numeric_limits<float>::max();
  s.max_distance_m = std::numeric_limits<float>::lowest();
  for (std::size_t i = 0; i < g.cells.size(); ++i) {
    if (g.cells[i] == Cell::kUnknown) ++s.unknown;
    if (g.cells[i] == Cell::kNoBlock) ++s.outside;
    if (g.cells[i] != Cell::kKnown) continue;
    ++s.known;
    s.min_distance_m = std::min(s.min_distance_m, g.distance_m[i]);
    s.max_distance_m = std::max(s.max_distance_m, g.distance_m[i]);
  }
  if (s.known == 0) s.min_distance_m = s.max_distance_m = 0.0f;
  // Spend the ramp on the distances present: up to the slice's largest, rounded up to a tick.
  s.colour_min_m = std::max(-max_distance_m, std::min(0.0f, s.min_distance_m));
  const float top_m = std::max(s.max_distance_m, s.colour_min_m + 0.1f);
  const float step = slice_detail::tickStep(top_m - s.colour_min_m);
  s.colour_max_m = std::min(max_distance_m, std::ceil(top_m / step - 1e-4f) * step);
  if (s.colour_max_m <= s.colour_min_m) s.colour_max_m = s.colour_min_m + step;
  return s;
}

void drawMap(ColorImage& image, const Layout& l, const SliceGrid& g, const EsdfSliceStats& s) {
  const int ppv = s.pixels_per_voxel;
  const float range_m = s.colour_max_m - s.colour_min_m;
  for (int row = 0; row < l.map_h; ++row) {
    const int gy = g.ny - 1 - row / ppv;  // y up
    for (int col = 0; col < l.map_w; ++col) {
      const std::size_t i = static_cast<std::size_t>(gy) * g.nx + col / ppv;
      const int x = l.map_x + col, y = l.map_y + row;
      Rgb colour = kNoBlockColour;
      if (g.cells[i] == Cell::kUnknown) colour = slice_detail::hatch(x, y);
      if (g.cells[i] == Cell::kKnown) {
        colour = esdfColour((g.distance_m[i] - s.colour_min_m) / range_m);
      }
      slice_detail::setPixel(image, x, y, colour);
    }
  }
}

std::string defaultTitle(const EsdfMap& map, float z_m) {
  char text[128];
  std::snprintf(text, sizeof(text), "ESDF AT Z=%.2f M (VOXEL %.3g M), SIGNED DISTANCE IN M",
                static_cast<double>(z_m), static_cast<double>(map.voxel_size_m));
  return text;
}

}  // namespace

EsdfSlice renderEsdfSlice(const EsdfMap& map, const EsdfSliceOptions& options) {
  validate(map, options);
  const SliceGrid grid = sliceGrid(map, options.z_m);
  EsdfSlice out;
  out.stats = gridStats(grid, options.max_distance_m);
  const int longer = std::max(grid.nx, grid.ny);
  out.stats.pixels_per_voxel = std::clamp((options.min_map_px + longer - 1) / longer, 1, 16);
  const int ppv = out.stats.pixels_per_voxel;
  const std::string title = options.title.empty() ? defaultTitle(map, options.z_m) : options.title;
  const Layout layout = slice_detail::layoutSlice(grid.nx * ppv, grid.ny * ppv, title);
  out.image = ColorImage(layout.width, layout.height, 255);
  drawText(out.image, slice_detail::kPad, slice_detail::kPad, title, slice_detail::kTextScale,
           {{20, 20, 20}});
  drawMap(out.image, layout, grid, out.stats);
  out.stats.map_x_px = layout.map_x;
  out.stats.map_y_px = layout.map_y;
  out.stats.grid_x0_voxels = grid.x0;
  out.stats.grid_y0_voxels = grid.y0;
  slice_detail::drawColourBar(out.image, layout, out.stats.colour_min_m, out.stats.colour_max_m);
  slice_detail::drawLegend(out.image, layout);
  return out;
}

Eigen::Vector2f slicePixel(const EsdfSliceStats& s, float voxel_size_m, float x_m, float y_m) {
  const float ppv = static_cast<float>(s.pixels_per_voxel);
  const float col = (x_m / voxel_size_m - static_cast<float>(s.grid_x0_voxels)) * ppv;
  const float row = (static_cast<float>(s.height_voxels) -
                     (y_m / voxel_size_m - static_cast<float>(s.grid_y0_voxels))) *
                    ppv;
  return Eigen::Vector2f(static_cast<float>(s.map_x_px) + col,
                         static_cast<float>(s.map_y_px) + row);
}

EsdfSliceStats writeEsdfSlicePng(const std::string& path, const EsdfMap& map,
                                 const EsdfSliceOptions& options) {
  const EsdfSlice slice = renderEsdfSlice(map, options);
  writeColorPng(path, slice.image);
  return slice.stats;
}

}  // namespace strata::apps
