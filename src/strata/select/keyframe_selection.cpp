#include "strata/select/keyframe_selection.h"

#include <algorithm>
#include <functional>

#include "strata/core/error.h"

namespace strata::selection {
namespace {

std::vector<double> metric(const std::vector<KeyframeScore>& scores,
                           const std::function<double(const KeyframeScore&)>& get) {
  std::vector<double> out;
  out.reserve(scores.size());
  for (const auto& s : scores) out.push_back(get(s));
  return out;
}

std::vector<std::uint8_t> dilate(const std::vector<std::uint8_t>& triggered, int radius) {
  std::vector<std::uint8_t> out(triggered.size(), 0);
  const int n = static_cast<int>(triggered.size());
  for (int i = 0; i < n; ++i) {
    if (!triggered[i]) continue;
    for (int j = std::max(0, i - radius); j <= std::min(n - 1, i + radius); ++j) out[j] = 1;
  }
  return out;
}

bool triggeredOurs(const TrajectorySelection& s, std::size_t i, const Thresholds& t) {
  return (t.coverage >= 0.0 && s.coverage[i] < t.coverage) ||
         (t.color_change >= 0.0 && s.color_change[i] > t.color_change) ||
         (t.depth_change_m >= 0.0 && s.depth_change_m[i] > t.depth_change_m) ||
         (t.surface_change >= 0.0 && s.surface_change[i] > t.surface_change);
}

}  // namespace

const char* methodName(Method method) {
  switch (method) {
    case Method::kReprojection:
      return "reproj";
    case Method::kNcc:
      return "ncc";
    case Method::kHistogram:
      return "hist";
  }
  return "?";
}

Method parseMethod(const std::string& name) {
  if (name == "reproj") return Method::kReprojection;
  if (name == "ncc") return Method::kNcc;
  if (name == "hist") return Method::kHistogram;
  throw InputError("method '" + name + "': expected reproj, ncc or hist");
}

void SelectionConfig::validate() const {
  if (smoothing_window < 1 || smoothing_window % 2 == 0) {
    throw InputError("smoothing_window must be odd and >= 1, got " +
                     std::to_string(smoothing_window));
  }
  if (dilation < 0) throw InputError("dilation must be >= 0");
}

std::size_t TrajectorySelection::selectedCount() const {
  return static_cast<std::size_t>(std::count(selected.begin(), selected.end(), 1));
}

std::vector<double> movingAverage(const std::vector<double>& values, int window) {
  const int n = static_cast<int>(values.size());
  const int half = window / 2;
  std::vector<double> out(values.size(), 0.0);
  for (int i = 0; i < n; ++i) {
    const int lo = std::max(0, i - half), hi = std::min(n - 1, i + half);
    double sum = 0.0;
    for (int j = lo; j <= hi; ++j) sum += values[j];
    out[i] = sum / (hi - lo + 1);
  }
  return out;
}

TrajectorySelection selectKeyframes(const std::vector<KeyframeScore>& scores,
                                    const SelectionConfig& config) {
  config.validate();
  const int w = config.smoothing_window;
  TrajectorySelection s;
  s.coverage = movingAverage(metric(scores, [](auto& k) { return k.coverage; }), w);
  s.color_change = movingAverage(metric(scores, [](auto& k) { return k.color_change; }), w);
  s.depth_change_m = movingAverage(metric(scores, [](auto& k) { return k.depth_change_m; }), w);
  s.surface_change = movingAverage(metric(scores, [](auto& k) { return k.surface_change; }), w);
  s.similarity.assign(scores.size(), 0.0);
  if (config.method == Method::kNcc) {
    s.similarity = movingAverage(metric(scores, [](auto& k) { return k.ncc; }), w);
  } else if (config.method == Method::kHistogram) {
    s.similarity = movingAverage(metric(scores, [](auto& k) { return k.histogram; }), w);
  }
  const Thresholds& t = config.thresholds;
  s.triggered.assign(scores.size(), 0);
  for (std::size_t i = 0; i < scores.size(); ++i) {
    switch (config.method) {
      case Method::kReprojection:
        s.triggered[i] = triggeredOurs(s, i, t);
        break;
      case Method::kNcc:
        s.triggered[i] = s.similarity[i] < t.ncc;
        break;
      case Method::kHistogram:
        s.triggered[i] = s.similarity[i] < t.histogram;
        break;
    }
  }
  s.selected = dilate(s.triggered, config.dilation);
  return s;
}

Thresholds autoThresholds(const std::vector<KeyframeScore>& first_session, int smoothing_window,
                          const Thresholds& base) {
  if (first_session.empty()) throw InputError("automatic thresholds need a scored first session");
  SelectionConfig config;
  config.smoothing_window = smoothing_window;
  const auto smoothed = [&](Method m) {
    config.method = m;
    return selectKeyframes(first_session, config);
  };
  const TrajectorySelection reproj = smoothed(Method::kReprojection);
  const TrajectorySelection ncc = smoothed(Method::kNcc);
  const TrajectorySelection hist = smoothed(Method::kHistogram);
  Thresholds t = base;
  t.coverage = *std::min_element(reproj.coverage.begin(), reproj.coverage.end());
  t.depth_change_m = *std::max_element(reproj.depth_change_m.begin(), reproj.depth_change_m.end());
  const double color = *std::max_element(reproj.color_change.begin(), reproj.color_change.end());
  if (color > 0.0) {  // the session had colour
    t.color_change = color;
    t.ncc = *std::min_element(ncc.similarity.begin(), ncc.similarity.end());
    t.histogram = *std::min_element(hist.similarity.begin(), hist.similarity.end());
  }
  return t;
}

std::string keyframeReason(const KeyframeScore& s, const Thresholds& thresholds) {
  const auto used = [](double threshold) { return threshold >= 0.0; };  // < 0: not used
  if (used(thresholds.coverage) && s.coverage < thresholds.coverage) {
    return "coverage " + std::to_string(s.coverage) + " below " +
           std::to_string(thresholds.coverage) + " (new space)";
  }
  if (used(thresholds.color_change) && s.color_change > thresholds.color_change) {
    return "colour change " + std::to_string(s.color_change) + " above " +
           std::to_string(thresholds.color_change);
  }
  if (used(thresholds.depth_change_m) && s.depth_change_m > thresholds.depth_change_m) {
    return "depth change " + std::to_string(s.depth_change_m) + " m above " +
           std::to_string(thresholds.depth_change_m) + " m";
  }
  if (used(thresholds.surface_change) && s.surface_change > thresholds.surface_change) {
    return "surface change " + std::to_string(s.surface_change) + " above " +
           std::to_string(thresholds.surface_change) + " (measured surface the map lacks)";
  }
  return "";
}

}  // namespace strata::selection
