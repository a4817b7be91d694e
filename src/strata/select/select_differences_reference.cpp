// Host reference of shaders/sample_differences.comp (see select_differences.h).
#include <algorithm>
#include <array>
#include <cmath>

#include "strata/select/select_differences.h"

namespace strata {
namespace {

using Rgb = std::array<float, 3>;

Rgb unpackRgb(std::uint32_t word) {
  return {static_cast<float>(word & 255u), static_cast<float>((word >> 8) & 255u),
          static_cast<float>((word >> 16) & 255u)};
}

/// 3 * rgb / max(r + g + b, 30): a change of light direction or intensity scales a pixel's three
/// channels alike under Lambertian shading, which this removes; dark pixels keep noise bounded.
Rgb chromaticity(const Rgb& rgb) {
  const float scale = 3.0f / std::max(rgb[0] + rgb[1] + rgb[2], 30.0f);
  return {rgb[0] * scale, rgb[1] * scale, rgb[2] * scale};
}

/// The blurred chromaticity difference at one hit sample (the shader's loop, in its order).
float colorDifference(const SampleRaycast& r, const std::vector<std::uint32_t>& observed_rgb,
                      int gx, int gy) {
  const SampleGrid& g = r.grid;
  Rgb rendered{0, 0, 0}, observed{0, 0, 0};
  float weight = 0.0f;
  for (int dy = -1; dy <= 1; ++dy) {
    for (int dx = -1; dx <= 1; ++dx) {
      const int u = gx + dx, v = gy + dy;
      if (u < 0 || v < 0 || u >= g.width || v >= g.height || !r.hit[v * g.width + u]) continue;
      const float w = static_cast<float>(2 - std::abs(dx)) * static_cast<float>(2 - std::abs(dy));
      const Rgb a = unpackRgb(r.color_rgba[v * g.width + u]);
      const Rgb b = unpackRgb(observed_rgb[v * g.width + u]);
      for (int c = 0; c < 3; ++c) rendered[c] += w * a[c], observed[c] += w * b[c];
      weight += w;
    }
  }
  for (int c = 0; c < 3; ++c) rendered[c] /= weight, observed[c] /= weight;
  const Rgb x = chromaticity(rendered), y = chromaticity(observed);
  return (std::abs(x[0] - y[0]) + std::abs(x[1] - y[1]) + std::abs(x[2] - y[2])) / 3.0f;
}

}  // namespace

void keyframeAtSamples(const SampleGrid& grid, const RgbdFrame& frame, std::vector<float>& depth_m,
                       std::vector<std::uint32_t>& color_rgb) {
  depth_m.assign(grid.count(), 0.0f);
  color_rgb.assign(grid.count(), 0u);
  for (int gy = 0; gy < grid.height; ++gy) {
    for (int gx = 0; gx < grid.width; ++gx) {
      const int i = gy * grid.width + gx;
      const std::size_t pixel = static_cast<std::size_t>(grid.pixelV(gy)) * frame.depth.width_px +
                                static_cast<std::size_t>(grid.pixelU(gx));
      const float d = frame.depth.depth_m.at(pixel);
      depth_m[i] = std::isfinite(d) && d > 0.0f ? d : 0.0f;
      if (frame.color.empty()) continue;
      const std::uint8_t* rgb = &frame.color.rgb.at(pixel * 3);
      color_rgb[i] = rgb[0] | (static_cast<std::uint32_t>(rgb[1]) << 8) |
                     (static_cast<std::uint32_t>(rgb[2]) << 16);
    }
  }
}

SampleDifferences sampleDifferencesReference(const SampleRaycast& r, const RgbdFrame& frame,
                                             const SampleDifferenceOptions& options) {
  std::vector<float> new_depth_m;
  std::vector<std::uint32_t> observed_rgb;
  keyframeAtSamples(r.grid, frame, new_depth_m, observed_rgb);
  const std::size_t n = static_cast<std::size_t>(r.grid.count());
  SampleDifferences out;
  out.color.assign(n, -1.0f);
  out.depth_m.assign(n, -1.0f);
  for (int gy = 0; gy < r.grid.height; ++gy) {
    for (int gx = 0; gx < r.grid.width; ++gx) {
      const std::size_t i = static_cast<std::size_t>(gy) * r.grid.width + gx;
      if (!r.hit[i]) continue;
      if (new_depth_m[i] > 0.0f) {
        const float beyond = std::abs(new_depth_m[i] - r.depth_m[i]) - options.depth_tolerance_m;
        out.depth_m[i] = std::clamp(beyond, 0.0f, options.max_depth_difference_m);
      }
      if (!frame.color.empty()) out.color[i] = colorDifference(r, observed_rgb, gx, gy);
    }
  }
  return out;
}

}  // namespace strata
