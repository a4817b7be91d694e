// Colour ramp, layout, colour bar with ticks and the legend of the ESDF slice picture.
#include "cli/esdf_slice_legend.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "cli/esdf_slice.h"

namespace strata::apps {

Rgb esdfColour(float t) {
  // Nine samples of matplotlib's viridis (perceptually uniform, readable in grey and by most
  // colour-blind viewers), linearly interpolated.
  static constexpr float kRamp[9][3] = {{68, 1, 84},    {71, 44, 122},  {59, 81, 139},
                                        {44, 113, 142}, {33, 144, 141}, {39, 173, 129},
                                        {92, 200, 99},  {170, 220, 50}, {253, 231, 37}};
  const float x = std::clamp(std::isfinite(t) ? t : 0.0f, 0.0f, 1.0f) * 8.0f;
  const int i = std::min(7, static_cast<int>(x));
  const float f = x - static_cast<float>(i);
  Rgb out;
  for (int k = 0; k < 3; ++k) {
    out[k] = static_cast<std::uint8_t>(std::lround(kRamp[i][k] * (1.0f - f) + kRamp[i + 1][k] * f));
  }
  return out;
}

namespace slice_detail {
namespace {

constexpr Rgb kInk = {{20, 20, 20}};
constexpr int kGlyphPx = kGlyphHeight * kTextScale;

/// "0.25", "-0.5", "2": at most two decimals, no trailing zeros.
std::string tickLabel(float value_m) {
  char text[32];
  std::snprintf(text, sizeof(text), "%.2f", static_cast<double>(value_m));
  std::string s = text;
  while (s.back() == '0') s.pop_back();
  if (s.back() == '.') s.pop_back();
  return s == "-0" ? "0" : s;
}

}  // namespace

float tickStep(float range_m) {
  for (float decade = 0.01f; decade < 1e4f; decade *= 10.0f) {
    for (const float m : {1.0f, 2.0f, 2.5f, 5.0f}) {
      if (range_m / (m * decade) <= 8.0f) return m * decade;
    }
  }
  return range_m;
}

namespace {

void drawHLine(ColorImage& image, int x0, int x1, int y, Rgb colour) {
  for (int x = x0; x <= x1; ++x) setPixel(image, x, y, colour);
}

void drawFrame(ColorImage& image, int x0, int y0, int w, int h) {
  drawHLine(image, x0 - 1, x0 + w, y0 - 1, kInk);
  drawHLine(image, x0 - 1, x0 + w, y0 + h, kInk);
  for (int y = y0 - 1; y <= y0 + h; ++y) {
    setPixel(image, x0 - 1, y, kInk);
    setPixel(image, x0 + w, y, kInk);
  }
}

}  // namespace

void setPixel(ColorImage& image, int x, int y, Rgb colour) {
  if (x < 0 || y < 0 || x >= image.width_px || y >= image.height_px) return;
  const std::size_t i = (static_cast<std::size_t>(y) * image.width_px + x) * 3;
  for (int k = 0; k < 3; ++k) image.rgb[i + k] = colour[k];
}

Layout layoutSlice(int map_w, int map_h, const std::string& title) {
  Layout l;
  l.map_x = kPad;
  l.map_y = kPad + kGlyphPx + kPad;
  l.map_w = map_w;
  l.map_h = map_h;
  const int content_h = std::max(map_h, kMinContentPx);
  l.bar_x = l.map_x + map_w + kBarGap;
  l.bar_y = l.map_y + kGlyphPx / 2;  // room for the top label
  l.legend_y = l.map_y + content_h - 2 * (kGlyphPx + 8);
  l.bar_h = l.legend_y - 16 - kGlyphPx / 2 - l.bar_y;
  const int labels_w = std::max(textWidth("-0.25", kTextScale), textWidth("NO BLOCK", kTextScale));
  l.width = std::max(l.bar_x + kBarWidth + 10 + labels_w + kPad,
                     kPad + textWidth(title, kTextScale) + kPad);
  l.height = l.map_y + content_h + kPad;
  return l;
}

void drawColourBar(ColorImage& image, const Layout& l, float lo_m, float hi_m) {
  for (int row = 0; row < l.bar_h; ++row) {
    const float t = 1.0f - static_cast<float>(row) / static_cast<float>(std::max(1, l.bar_h - 1));
    const Rgb colour = esdfColour(t);
    drawHLine(image, l.bar_x, l.bar_x + kBarWidth - 1, l.bar_y + row, colour);
  }
  drawFrame(image, l.bar_x, l.bar_y, kBarWidth, l.bar_h);
  const float step = tickStep(hi_m - lo_m);
  const int first = static_cast<int>(std::ceil(lo_m / step - 1e-4f));
  const int last = static_cast<int>(std::floor(hi_m / step + 1e-4f));
  for (int k = first; k <= last; ++k) {
    const float v = static_cast<float>(k) * step;
    const float t = (v - lo_m) / (hi_m - lo_m);
    const int y = l.bar_y + static_cast<int>(std::lround((1.0f - t) * (l.bar_h - 1)));
    // Short tick, then a clear gap so it does not read as a minus sign.
    drawHLine(image, l.bar_x + kBarWidth, l.bar_x + kBarWidth + 3, y, kInk);
    drawText(image, l.bar_x + kBarWidth + 10, y - kGlyphPx / 2, tickLabel(v), kTextScale, kInk);
  }
}

void drawLegend(ColorImage& image, const Layout& l) {
  const int swatch_h = kGlyphPx;
  for (int n = 0; n < 2; ++n) {
    const int y0 = l.legend_y + n * (swatch_h + 8);
    for (int y = y0; y < y0 + swatch_h; ++y) {
      for (int x = l.bar_x; x < l.bar_x + kBarWidth; ++x) {
        setPixel(image, x, y, n == 0 ? hatch(x, y) : kNoBlockColour);
      }
    }
    drawFrame(image, l.bar_x, y0, kBarWidth, swatch_h);
    drawText(image, l.bar_x + kBarWidth + 10, y0, n == 0 ? "UNKNOWN" : "NO BLOCK", kTextScale,
             kInk);
  }
}

}  // namespace slice_detail
}  // namespace strata::apps
