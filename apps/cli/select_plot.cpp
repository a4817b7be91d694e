#include "cli/select_plot.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "cli/esdf_slice_font.h"

namespace strata::apps {
namespace {

constexpr int kWidth = 960;
constexpr int kPanelHeight = 150;
constexpr int kMargin = 40;
constexpr int kStripHeight = 24;
constexpr Rgb kBackground = {255, 255, 255};
constexpr Rgb kAxis = {120, 120, 120};
constexpr Rgb kCurve = {30, 90, 200};
constexpr Rgb kThreshold = {210, 40, 40};
constexpr Rgb kSelected = {40, 160, 70};
constexpr Rgb kTruePositive = {70, 70, 190};
constexpr Rgb kText = {20, 20, 20};

struct Panel {
  std::string label;
  const std::vector<double>* values;
  double threshold;
};

void put(ColorImage& im, int x, int y, Rgb c) {
  if (x < 0 || y < 0 || x >= im.width_px || y >= im.height_px) return;
  std::uint8_t* p = &im.rgb[(static_cast<std::size_t>(y) * im.width_px + x) * 3];
  p[0] = c[0], p[1] = c[1], p[2] = c[2];
}

void fillRect(ColorImage& im, int x0, int y0, int x1, int y1, Rgb c) {
  for (int y = y0; y < y1; ++y) {
    for (int x = x0; x < x1; ++x) put(im, x, y, c);
  }
}

void line(ColorImage& im, int x0, int y0, int x1, int y1, Rgb c) {
  const int steps = std::max({std::abs(x1 - x0), std::abs(y1 - y0), 1});
  for (int s = 0; s <= steps; ++s) {
    put(im, x0 + (x1 - x0) * s / steps, y0 + (y1 - y0) * s / steps, c);
    put(im, x0 + (x1 - x0) * s / steps, y0 + (y1 - y0) * s / steps + 1, c);
  }
}

int keyframeX(std::size_t i, std::size_t n) {
  const int span = kWidth - 2 * kMargin;
  return kMargin + (n > 1 ? static_cast<int>(span * i / (n - 1)) : span / 2);
}

void drawPanel(ColorImage& im, int top, const Panel& p,
               const std::vector<std::uint8_t>& triggered) {
  const std::vector<double>& v = *p.values;
  double lo = std::min(p.threshold, *std::min_element(v.begin(), v.end()));
  double hi = std::max(p.threshold, *std::max_element(v.begin(), v.end()));
  if (hi - lo < 1e-9) hi = lo + 1.0;
  const double pad = 0.08 * (hi - lo);
  lo -= pad, hi += pad;
  const int plot_top = top + 16, plot_bottom = top + kPanelHeight - 6;
  const auto y_of = [&](double value) {
    return plot_bottom - static_cast<int>((value - lo) / (hi - lo) * (plot_bottom - plot_top));
  };
  line(im, kMargin, plot_bottom, kWidth - kMargin, plot_bottom, kAxis);
  line(im, kMargin, plot_top, kMargin, plot_bottom, kAxis);
  char label[128];
  std::snprintf(label, sizeof(label), "%s  (threshold %.3f, range %.3f to %.3f)", p.label.c_str(),
                p.threshold, lo + pad, hi - pad);
  drawText(im, kMargin, top + 2, label, 2, kText);
  const int ty = y_of(p.threshold);
  for (int x = kMargin; x < kWidth - kMargin; x += 8) line(im, x, ty, x + 4, ty, kThreshold);
  for (std::size_t i = 0; i + 1 < v.size(); ++i) {
    line(im, keyframeX(i, v.size()), y_of(v[i]), keyframeX(i + 1, v.size()), y_of(v[i + 1]),
         kCurve);
  }
  for (std::size_t i = 0; i < v.size(); ++i) {
    const int x = keyframeX(i, v.size()), y = y_of(v[i]);
    fillRect(im, x - 2, y - 2, x + 3, y + 3, triggered[i] ? kThreshold : kCurve);
  }
}

std::vector<Panel> panelsOf(const selection::TrajectorySelection& s,
                            const selection::SelectionConfig& c) {
  const selection::Thresholds& t = c.thresholds;
  switch (c.method) {
    case selection::Method::kNcc:
      return {{"NCC SIMILARITY", &s.similarity, t.ncc}};
    case selection::Method::kHistogram:
      return {{"HISTOGRAM CORRELATION", &s.similarity, t.histogram}};
    case selection::Method::kReprojection:
      break;
  }
  std::vector<Panel> panels = {{"COVERAGE", &s.coverage, t.coverage}};
  if (t.color_change >= 0.0) panels.push_back({"COLOUR CHANGE", &s.color_change, t.color_change});
  if (t.depth_change_m >= 0.0) {
    panels.push_back({"DEPTH CHANGE (M)", &s.depth_change_m, t.depth_change_m});
  }
  if (t.surface_change >= 0.0) {
    panels.push_back({"SURFACE CHANGE", &s.surface_change, t.surface_change});
  }
  return panels;
}

}  // namespace

ColorImage renderSelectionPlot(const selection::TrajectorySelection& s,
                               const selection::SelectionConfig& config,
                               const std::vector<std::uint8_t>& truth) {
  const std::vector<Panel> panels = panelsOf(s, config);
  const int strip_top = static_cast<int>(panels.size()) * kPanelHeight + 8;
  const bool with_truth = !truth.empty() && truth.size() == s.selected.size();
  const int truth_top = strip_top + kStripHeight + 4;
  const int caption_top = with_truth ? truth_top + kStripHeight + 8 : strip_top + kStripHeight + 8;
  ColorImage im(kWidth, caption_top + 44 + (with_truth ? 20 : 0), 255);
  fillRect(im, 0, 0, im.width_px, im.height_px, kBackground);
  if (s.selected.empty()) return im;
  for (std::size_t p = 0; p < panels.size(); ++p) {
    drawPanel(im, static_cast<int>(p) * kPanelHeight, panels[p], s.triggered);
  }
  const std::size_t n = s.selected.size();
  const int half =
      std::max(1, (kWidth - 2 * kMargin) / static_cast<int>(2 * std::max<std::size_t>(n, 1)));
  for (std::size_t i = 0; i < n; ++i) {
    const int x = keyframeX(i, n);
    fillRect(im, x - half, strip_top, x + half, strip_top + kStripHeight,
             s.selected[i] ? kSelected : Rgb{225, 225, 225});
    if (with_truth) {
      fillRect(im, x - half, truth_top, x + half, truth_top + kStripHeight,
               truth[i] ? kTruePositive : Rgb{225, 225, 225});
    }
  }
  char caption[160];
  std::snprintf(caption, sizeof(caption), "%s: %zu OF %zu KEYFRAMES SELECTED (GREEN)",
                selection::methodName(config.method), s.selectedCount(), n);
  drawText(im, kMargin, caption_top, caption, 2, kText);
  drawText(im, kMargin, caption_top + 20,
           "RED DOTS: KEYFRAMES OVER A THRESHOLD (DASHED) BEFORE DILATION", 2, kText);
  if (with_truth) {
    std::size_t positives = 0;
    for (std::uint8_t t : truth) positives += t ? 1 : 0;
    std::snprintf(caption, sizeof(caption),
                  "LOWER STRIP: %zu KEYFRAMES THAT TRULY SEE CHANGE OR UNMAPPED SPACE (BLUE)",
                  positives);
    drawText(im, kMargin, caption_top + 40, caption, 2, kText);
  }
  return im;
}

ColorImage thumbnail(const ColorImage& image) {
  ColorImage out(image.width_px / 4, image.height_px / 4);
  for (int y = 0; y < out.height_px; ++y) {
    for (int x = 0; x < out.width_px; ++x) {
      for (int c = 0; c < 3; ++c) {
        int sum = 0;
        for (int dy = 1; dy <= 2; ++dy) {
          for (int dx = 1; dx <= 2; ++dx) {
            sum +=
                image.rgb[((static_cast<std::size_t>(4 * y + dy)) * image.width_px + 4 * x + dx) *
                              3 +
                          c];
          }
        }
        out.rgb[(static_cast<std::size_t>(y) * out.width_px + x) * 3 + c] =
            static_cast<std::uint8_t>(sum / 4);
      }
    }
  }
  return out;
}

ColorImage renderContactSheet(const std::vector<ColorImage>& thumbnails,
                              const std::vector<std::size_t>& labels, std::size_t max_images) {
  std::vector<std::size_t> pick;
  const std::size_t n = thumbnails.size();
  const std::size_t shown = std::min(n, max_images);
  for (std::size_t k = 0; k < shown; ++k) pick.push_back(k * n / shown);
  if (pick.empty()) {
    ColorImage empty(320, 40, 255);
    drawText(empty, 8, 12, "NO KEYFRAME SELECTED", 2, kText);
    return empty;
  }
  const int tw = thumbnails[0].width_px, th = thumbnails[0].height_px, gap = 4, label_h = 18;
  const int columns = std::min<int>(6, static_cast<int>(pick.size()));
  const int rows = (static_cast<int>(pick.size()) + columns - 1) / columns;
  ColorImage sheet(columns * (tw + gap) + gap, rows * (th + label_h + gap) + gap, 255);
  for (std::size_t k = 0; k < pick.size(); ++k) {
    const ColorImage& t = thumbnails[pick[k]];
    const int x0 = gap + static_cast<int>(k % columns) * (tw + gap);
    const int y0 = gap + static_cast<int>(k / columns) * (th + label_h + gap);
    for (int y = 0; y < std::min(th, t.height_px); ++y) {
      for (int x = 0; x < std::min(tw, t.width_px); ++x) {
        const std::uint8_t* p = &t.rgb[(static_cast<std::size_t>(y) * t.width_px + x) * 3];
        put(sheet, x0 + x, y0 + label_h + y, {p[0], p[1], p[2]});
      }
    }
    drawText(sheet, x0 + 2, y0 + 2, "KEYFRAME " + std::to_string(labels[pick[k]]), 2, kText);
  }
  return sheet;
}

}  // namespace strata::apps
