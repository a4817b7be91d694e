// The scores of a repeat run against the truth (repeat_loop.h).
#include <algorithm>
#include <cmath>

#include "strata/repeat/repeat_loop.h"

namespace strata::repeat {

void scoreRepeat(RepeatResult& r, const TaughtPath& taught) {
  r.following_error_m.clear();
  double sum2 = 0.0;
  r.following_max_m = 0.0;
  for (const Eigen::Vector3f& p : r.true_W) {
    const float e = distanceToPolyline(p, taught.p_W);
    r.following_error_m.push_back(e);
    sum2 += static_cast<double>(e) * e;
    r.following_max_m = std::max(r.following_max_m, static_cast<double>(e));
  }
  r.following_rms_m =
      r.true_W.empty() ? 0.0 : std::sqrt(sum2 / static_cast<double>(r.true_W.size()));
  r.drift_max_m = 0.0;
  for (std::size_t i = 0; i < r.true_W.size(); ++i) {
    const double d = (r.estimate_M[i] - r.true_W[i]).norm();
    r.drift_max_m = std::max(r.drift_max_m, d);
    r.drift_final_m = d;
  }
  r.localized = r.accepted = r.rejected = 0;
  double sum_ms = 0.0;
  r.localize_ms_max = 0.0;
  for (const LocalizationRecord& l : r.localizations) {
    r.localized += l.localized ? 1 : 0;
    r.accepted += l.accepted ? 1 : 0;
    r.rejected += l.localized && !l.accepted ? 1 : 0;
    sum_ms += l.time_ms;
    r.localize_ms_max = std::max(r.localize_ms_max, l.time_ms);
  }
  r.localize_ms_mean =
      r.localizations.empty() ? 0.0 : sum_ms / static_cast<double>(r.localizations.size());
}

}  // namespace strata::repeat
