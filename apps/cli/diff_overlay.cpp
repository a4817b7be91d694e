// Layout of the label overlay: title, top view, legend, scale bar.
#include "cli/diff_overlay.h"

#include <algorithm>
#include <cmath>

#include "cli/diff_overlay_raster.h"
#include "strata/core/error.h"
#include "strata/io/image_io.h"

namespace strata::apps {
namespace {

using overlay_detail::TopImage;
using overlay_detail::TopView;

constexpr int kPad = 12;
constexpr int kTextScale = 2;
constexpr int kLineH = kGlyphHeight * kTextScale + 8;
constexpr int kSwatch = kGlyphHeight * kTextScale;
constexpr int kMaxLegendObjects = 20;
constexpr Rgb kInk = {{20, 20, 20}};
constexpr Rgb kSurface = {{190, 190, 190}};
// Distinct, saturated colours (Tableau 10) so neighbouring objects stay apart from the grey.
constexpr Rgb kPalette[] = {
    {{214, 39, 40}},  {{31, 119, 180}},  {{255, 127, 14}}, {{44, 160, 44}}, {{148, 103, 189}},
    {{23, 190, 207}}, {{227, 119, 194}}, {{188, 189, 34}}, {{140, 86, 75}}, {{127, 127, 127}}};

Rgb objectColour(int id) { return kPalette[static_cast<std::size_t>(id - 1) % 10]; }

TopView viewOf(const Mesh& surface, const OverlayOptions& o) {
  Eigen::AlignedBox3f box;
  for (const Eigen::Vector3f& v : surface.vertices) box.extend(v);
  if (box.isEmpty()) throw InputError("label overlay: the session's surface is empty");
  const Eigen::Vector3f size = box.sizes();
  TopView view;
  view.pixel_m = std::max(o.min_pixel_m, std::max(size.x(), size.y()) / float(o.max_map_px));
  view.origin_m = Eigen::Vector2f(box.min().x(), box.max().y());
  view.width = std::max(1, static_cast<int>(std::ceil(size.x() / view.pixel_m)));
  view.height = std::max(1, static_cast<int>(std::ceil(size.y() / view.pixel_m)));
  return view;
}

void fill(ColorImage& image, int x0, int y0, int w, int h, Rgb colour) {
  for (int y = std::max(0, y0); y < std::min(image.height_px, y0 + h); ++y) {
    for (int x = std::max(0, x0); x < std::min(image.width_px, x0 + w); ++x) {
      const std::size_t i = (static_cast<std::size_t>(y) * image.width_px + x) * 3;
      for (int k = 0; k < 3; ++k) image.rgb[i + k] = colour[k];
    }
  }
}

void blit(ColorImage& image, const TopImage& top, int x0, int y0) {
  for (int y = 0; y < top.view.height; ++y) {
    for (int x = 0; x < top.view.width; ++x) {
      fill(image, x0 + x, y0 + y, 1, 1,
           top.colour[static_cast<std::size_t>(y) * top.view.width + x]);
    }
  }
}

std::vector<std::pair<Rgb, std::string>> legendEntries(
    const std::vector<change::DiscoveredObject>& objects) {
  std::vector<std::pair<Rgb, std::string>> entries = {{kSurface, "UNCHANGED SURFACE"}};
  for (const auto& o : objects) {
    if (static_cast<int>(entries.size()) > kMaxLegendObjects) {
      entries.emplace_back(Rgb{{255, 255, 255}},
                           "+" + std::to_string(objects.size() - kMaxLegendObjects) + " MORE");
      break;
    }
    entries.emplace_back(objectColour(o.id), "OBJECT " + std::to_string(o.id));
  }
  return entries;
}

/// The object's id at its centroid, in ink on a white halo, so colours that repeat after ten
/// objects stay apart.
void drawIdLabel(ColorImage& image, const TopView& view, int x0, int y0,
                 const change::DiscoveredObject& object) {
  const std::string text = std::to_string(object.id);
  const Eigen::Vector2f p = view.toPixel(object.centroid);
  const int x = x0 + static_cast<int>(p.x()) - textWidth(text, kTextScale) / 2;
  const int y = y0 + static_cast<int>(p.y()) - kGlyphHeight * kTextScale / 2;
  for (int dy = -1; dy <= 1; ++dy) {
    for (int dx = -1; dx <= 1; ++dx)
      drawText(image, x + dx, y + dy, text, kTextScale, {{255, 255, 255}});
  }
  drawText(image, x, y, text, kTextScale, kInk);
}

/// A bar of whole metres (at least 1 m, at most a third of the map) with its label.
void drawScaleBar(ColorImage& image, int x0, int y0, int map_w, float pixel_m) {
  const int metres = std::max(1, static_cast<int>(map_w * pixel_m / 3.0f));
  const int length = static_cast<int>(std::lround(metres / pixel_m));
  fill(image, x0, y0, length, 4, kInk);
  drawText(image, x0 + length + 8, y0 - 4, std::to_string(metres) + " M", kTextScale, kInk);
}

}  // namespace

ColorImage renderOverlay(const Mesh& surface, const std::vector<change::DiscoveredObject>& objects,
                         const OverlayOptions& options) {
  if (options.max_map_px < 16 || !(options.min_pixel_m > 0.0f)) {
    throw InputError("label overlay: max_map_px must be >= 16 and min_pixel_m positive");
  }
  TopImage top = overlay_detail::makeTopImage(viewOf(surface, options));
  overlay_detail::drawMesh(top, surface, kSurface, 0.0f);
  // Objects are faces of the same surface: a small negative bias lets them win the tie.
  for (const auto& o : objects) overlay_detail::drawMesh(top, o.mesh, objectColour(o.id), -0.01f);
  const auto entries = legendEntries(objects);
  const int map_y = kPad + kLineH + kPad;
  const int legend_x = kPad + top.view.width + 2 * kPad;
  int legend_w = 0;
  for (const auto& e : entries) legend_w = std::max(legend_w, textWidth(e.second, kTextScale));
  const int width = std::max(legend_x + kSwatch + 8 + legend_w + kPad,
                             2 * kPad + textWidth(options.title, kTextScale));
  const int height =
      std::max(map_y + top.view.height + kPad + kLineH, map_y + int(entries.size()) * kLineH) +
      kPad;
  ColorImage image(width, height, 255);
  drawText(image, kPad, kPad, options.title, kTextScale, kInk);
  blit(image, top, kPad, map_y);
  for (const auto& o : objects) drawIdLabel(image, top.view, kPad, map_y, o);
  for (std::size_t i = 0; i < entries.size(); ++i) {
    const int y = map_y + static_cast<int>(i) * kLineH;
    fill(image, legend_x - 1, y - 1, kSwatch + 2, kSwatch + 2, kInk);
    fill(image, legend_x, y, kSwatch, kSwatch, entries[i].first);
    drawText(image, legend_x + kSwatch + 8, y, entries[i].second, kTextScale, kInk);
  }
  drawScaleBar(image, kPad, map_y + top.view.height + kPad + 4, top.view.width, top.view.pixel_m);
  return image;
}

void writeOverlayPng(const std::string& path, const Mesh& surface,
                     const std::vector<change::DiscoveredObject>& objects,
                     const OverlayOptions& options) {
  writeColorPng(path, renderOverlay(surface, objects, options));
}

}  // namespace strata::apps
