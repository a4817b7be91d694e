#pragma once
// Internal to esdf_slice.cpp: picture layout and the colour bar / legend drawing.
#include <string>

#include "cli/esdf_slice.h"

namespace strata::apps::slice_detail {

inline constexpr int kPad = 12;       // outer margin, pixels
inline constexpr int kTextScale = 2;  // font pixels are 2x2: 10x14 pixel glyphs
inline constexpr int kBarWidth = 24;
inline constexpr int kBarGap = 24;         // between the map and the colour bar
inline constexpr int kMinContentPx = 260;  // the bar needs room for its ticks and the legend

struct Layout {
  int width = 0, height = 0;
  int map_x = 0, map_y = 0, map_w = 0, map_h = 0;
  int bar_x = 0, bar_y = 0, bar_h = 0;
  int legend_y = 0;
};

/// Where everything goes for a map of map_w x map_h pixels and this title.
Layout layoutSlice(int map_w, int map_h, const std::string& title);

void setPixel(ColorImage& image, int x, int y, Rgb colour);

/// The smallest of the 1-2-2.5-5 steps that gives at most 8 intervals over the range.
float tickStep(float range_m);

/// Colour bar over [lo, hi] (top = hi) with ticks and labels, and the unknown / no-block legend.
void drawColourBar(ColorImage& image, const Layout& layout, float lo_m, float hi_m);
void drawLegend(ColorImage& image, const Layout& layout);

/// The unknown hatch at pixel (x, y).
inline Rgb hatch(int x, int y) { return kUnknownHatch[((x + y) / 4) % 2]; }

}  // namespace strata::apps::slice_detail
