#pragma once
// Trajectory-level keyframe selection: the per-keyframe metrics of a session, smoothed
// along the trajectory with a moving average, thresholded (coverage below / change above), and the
// selection dilated to neighbouring keyframes. Thresholds can be estimated automatically from the
// first session scored against its own reconstruction. Thread safe (pure functions).
#include <cstdint>
#include <string>
#include <vector>

#include "strata/select/keyframe_scorer.h"

namespace strata::selection {

/// Which metric decides: the raycast-reprojection metrics (coverage, colour change, depth change,
/// surface change) or a baseline image similarity (normalised cross-correlation, histogram
/// correlation), all on the same samples.
enum class Method { kReprojection, kNcc, kHistogram };
const char* methodName(Method method);  // "reproj", "ncc", "hist"
/// InputError for anything but "reproj", "ncc", "hist".
Method parseMethod(const std::string& name);

struct Thresholds {
  /// Ours: select when smoothed coverage < coverage, or colour change > color_change, or depth
  /// change > depth_change_m, or surface change > surface_change. A metric whose threshold is
  /// negative is not used.
  double coverage = 0.9;
  double color_change = 0.25;
  double depth_change_m = 0.05;
  /// Share of the measured samples the map may fail to hold before a keyframe is worth fusing:
  /// 2 % is ~60 samples of the 10 px grid, an object of 0.35 m at 2.5 m. autoThresholds does not
  /// estimate it (it keeps base's value).
  double surface_change = 0.02;
  /// Baselines: select when the smoothed similarity < this.
  double ncc = 0.5;
  double histogram = 0.5;
};

struct SelectionConfig {
  Method method = Method::kReprojection;
  /// Moving-average window along the trajectory, keyframes (odd; 1 = no smoothing). Wider rides
  /// out single noisy frames but blurs short events.
  int smoothing_window = 5;
  /// Keyframes added on each side of every triggered one: a change seen by a few frames is then
  /// reconstructed from its neighbours' viewpoints too.
  int dilation = 1;
  Thresholds thresholds;

  void validate() const;  // InputError naming the field
};

/// The smoothed metrics and decisions along one session's keyframes.
struct TrajectorySelection {
  std::vector<double> coverage;         // smoothed
  std::vector<double> color_change;     // smoothed
  std::vector<double> depth_change_m;   // smoothed
  std::vector<double> surface_change;   // smoothed
  std::vector<double> similarity;       // smoothed baseline similarity (ncc or hist; 0 for ours)
  std::vector<std::uint8_t> triggered;  // crossed a threshold (before dilation)
  std::vector<std::uint8_t> selected;   // after dilation
  std::size_t selectedCount() const;
};

/// Centred moving average; at the ends the window shrinks to the keyframes that exist.
std::vector<double> movingAverage(const std::vector<double>& values, int window);

TrajectorySelection selectKeyframes(const std::vector<KeyframeScore>& scores,
                                    const SelectionConfig& config);

/// Why one frame is a keyframe under `thresholds` (the first metric past its threshold, in the
/// order coverage, colour, depth, surface change), or "" when none is: the per-frame decision of
/// online scoring, without the trajectory smoothing and dilation of selectKeyframes.
std::string keyframeReason(const KeyframeScore& score, const Thresholds& thresholds);

/// Thresholds from the first session against its own reconstruction: the largest smoothed change
/// metrics and the smallest smoothed coverage / similarities it shows. Anything beyond what an
/// unchanged, fully mapped session produces counts as change. Keeps `base` for surface_change and
/// for metrics the session gives no value for (no colour: the colour thresholds stay as they were).
/// InputError when `first_session` is empty.
Thresholds autoThresholds(const std::vector<KeyframeScore>& first_session, int smoothing_window,
                          const Thresholds& base = {});

}  // namespace strata::selection
