// The host half of keyframe scoring: metrics from the raycast samples and the keyframe's images
// (keyframe_scorer.h). Both the device and the reference path end here, so they decide alike.
#include <algorithm>
#include <array>
#include <cmath>
#include <string>

#include "strata/core/error.h"
#include "strata/select/keyframe_scorer.h"

namespace strata::selection {
namespace {

using Rgb = std::array<float, 3>;

/// The keyframe's images at the sample pixels, beside the rendered ones.
struct SamplePairs {
  std::vector<Rgb> rendered;       // colour of the map at the hit (0 on a miss)
  std::vector<Rgb> observed;       // the keyframe's colour at the sample pixel
  std::vector<float> new_depth_m;  // the keyframe's depth, 0 where invalid
};

Rgb unpack(std::uint32_t rgba) {
  return {static_cast<float>(rgba & 255u), static_cast<float>((rgba >> 8) & 255u),
          static_cast<float>((rgba >> 16) & 255u)};
}

SamplePairs gatherPairs(const SampleRaycast& r, const RgbdFrame& frame) {
  std::vector<std::uint32_t> observed_rgb;
  SamplePairs p;
  keyframeAtSamples(r.grid, frame, p.new_depth_m, observed_rgb);
  p.rendered.resize(r.color_rgba.size());
  p.observed.resize(observed_rgb.size());
  for (std::size_t i = 0; i < p.rendered.size(); ++i) p.rendered[i] = unpack(r.color_rgba[i]);
  for (std::size_t i = 0; i < p.observed.size(); ++i) p.observed[i] = unpack(observed_rgb[i]);
  return p;
}

/// Mean of the upper half of the values ("mean plus"): a change over a small part of the image
/// still moves it, noise spread evenly moves it little.
double upperHalfMean(std::vector<float> values) {
  if (values.empty()) return 0.0;
  const std::size_t half = values.size() / 2;
  std::nth_element(values.begin(), values.begin() + half, values.end());
  double sum = 0.0;
  for (std::size_t i = half; i < values.size(); ++i) sum += values[i];
  return sum / static_cast<double>(values.size() - half);
}

/// Upper-half mean of the per-sample values that apply (>= 0).
double upperHalfMeanOf(const std::vector<float>& per_sample) {
  std::vector<float> values;
  for (float v : per_sample) {
    if (v >= 0.0f) values.push_back(v);
  }
  return upperHalfMean(std::move(values));
}

/// Share of the samples the map explains. With depth, only samples where the keyframe measured
/// depth count: beyond the sensor's range (through a door, down a corridor) neither image has
/// anything, and such samples must not read as new space. Without any valid depth: all samples.
double coverage(const SampleRaycast& r, const SamplePairs& p, int* hits) {
  int measured = 0, measured_hits = 0, all_hits = 0;
  for (std::size_t i = 0; i < r.hit.size(); ++i) {
    all_hits += r.hit[i];
    if (p.new_depth_m[i] <= 0.0f) continue;
    ++measured;
    measured_hits += r.hit[i];
  }
  if (measured == 0) {
    *hits = all_hits;
    return static_cast<double>(all_hits) / static_cast<double>(r.hit.size());
  }
  *hits = measured_hits;
  return static_cast<double>(measured_hits) / measured;
}

/// Share of the samples with a surface check whose measured point the map does not hold.
double surfaceChange(const SampleRaycast& r) {
  int checked = 0, not_held = 0;
  for (SurfaceCheck c : r.surface) {
    checked += c != SurfaceCheck::kNoMeasurement;
    not_held += c == SurfaceCheck::kNotHeld;
  }
  return checked > 0 ? static_cast<double>(not_held) / checked : 0.0;
}

float grey(const Rgb& rgb) { return (rgb[0] + rgb[1] + rgb[2]) / 3.0f; }

/// Pearson correlation of two equally long series; 1 when either is constant and both are equal,
/// 0 when only one is constant.
double correlation(const std::vector<double>& a, const std::vector<double>& b) {
  double ma = 0, mb = 0;
  for (std::size_t i = 0; i < a.size(); ++i) ma += a[i], mb += b[i];
  ma /= a.size(), mb /= b.size();
  double ab = 0, aa = 0, bb = 0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    ab += (a[i] - ma) * (b[i] - mb), aa += (a[i] - ma) * (a[i] - ma),
        bb += (b[i] - mb) * (b[i] - mb);
  }
  if (aa <= 0.0 || bb <= 0.0) return aa == bb ? 1.0 : 0.0;
  return ab / std::sqrt(aa * bb);
}

/// Baseline 1: normalised cross-correlation of the grey images (misses render black).
double nccSimilarity(const SamplePairs& p) {
  std::vector<double> a(p.rendered.size()), b(p.observed.size());
  for (std::size_t i = 0; i < a.size(); ++i) a[i] = grey(p.rendered[i]), b[i] = grey(p.observed[i]);
  return correlation(a, b);
}

/// Baseline 2: correlation of the grey-level histograms (misses render black).
double histogramSimilarity(const SamplePairs& p, int bins) {
  std::vector<double> a(bins, 0.0), b(bins, 0.0);
  const auto bin = [bins](float g) {
    return std::min(bins - 1, static_cast<int>(g * bins / 256.0f));
  };
  for (std::size_t i = 0; i < p.rendered.size(); ++i) {
    a[bin(grey(p.rendered[i]))] += 1.0;
    b[bin(grey(p.observed[i]))] += 1.0;
  }
  return correlation(a, b);
}

void checkSizes(const SampleRaycast& r, const RgbdFrame& frame) {
  const SampleGrid& g = r.grid;
  const bool grid_fits = g.width > 0 && g.height > 0 &&
                         g.pixelU(g.width - 1) < frame.depth.width_px &&
                         g.pixelV(g.height - 1) < frame.depth.height_px;
  const std::size_t n = static_cast<std::size_t>(g.count());
  if (!grid_fits || r.hit.size() != n || r.depth_m.size() != n || r.color_rgba.size() != n) {
    throw InputError("keyframe '" + frame.name + "': raycast samples do not fit its " +
                     std::to_string(frame.depth.width_px) + "x" +
                     std::to_string(frame.depth.height_px) + " depth image");
  }
  if (!r.surface.empty() && r.surface.size() != n) {
    throw InputError("keyframe '" + frame.name + "': surface checks do not fit its sample grid");
  }
  if (!frame.color.empty() && (frame.color.width_px != frame.depth.width_px ||
                               frame.color.height_px != frame.depth.height_px)) {
    throw InputError("keyframe '" + frame.name + "': colour and depth sizes differ");
  }
}

}  // namespace

void ScorerConfig::validate() const {
  if (sample_stride_px < 1) throw InputError("sample_stride_px must be >= 1");
  if (!(min_weight >= 0.0f)) throw InputError("min_weight must be >= 0");
  if (!(max_depth_difference_m > 0.0f)) throw InputError("max_depth_difference_m must be > 0");
  if (!(depth_tolerance_m >= 0.0f)) throw InputError("depth_tolerance_m must be >= 0");
  if (!(held_tolerance_voxels > 0.0f)) throw InputError("held_tolerance_voxels must be > 0");
  if (histogram_bins < 2) throw InputError("histogram_bins must be >= 2");
}

SampleDifferenceOptions differenceOptions(const ScorerConfig& config) {
  SampleDifferenceOptions options;
  options.depth_tolerance_m = config.depth_tolerance_m;
  options.max_depth_difference_m = config.max_depth_difference_m;
  return options;
}

KeyframeScore scoreSamples(const SampleRaycast& rendered, const RgbdFrame& frame,
                           const ScorerConfig& config) {
  checkSizes(rendered, frame);
  return scoreSamples(rendered, frame, config,
                      sampleDifferencesReference(rendered, frame, differenceOptions(config)));
}

KeyframeScore scoreSamples(const SampleRaycast& rendered, const RgbdFrame& frame,
                           const ScorerConfig& config, const SampleDifferences& differences) {
  checkSizes(rendered, frame);
  const std::size_t n = static_cast<std::size_t>(rendered.grid.count());
  if (differences.color.size() != n || differences.depth_m.size() != n) {
    throw InputError("keyframe '" + frame.name + "': sample differences do not fit its grid");
  }
  const SamplePairs pairs = gatherPairs(rendered, frame);
  KeyframeScore s;
  s.samples = rendered.grid.count();
  s.coverage = coverage(rendered, pairs, &s.hits);
  s.depth_change_m = upperHalfMeanOf(differences.depth_m);
  s.surface_change = surfaceChange(rendered);
  if (frame.color.empty()) {
    s.ncc = s.histogram = 1.0;  // nothing to compare: no evidence of change
    return s;
  }
  s.color_change = upperHalfMeanOf(differences.color);
  s.ncc = nccSimilarity(pairs);
  s.histogram = histogramSimilarity(pairs, config.histogram_bins);
  return s;
}

}  // namespace strata::selection
