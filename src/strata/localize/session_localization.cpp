// A recorded session localised frame by frame against a prior map.
#include "strata/localize/session_localization.h"

#include <algorithm>
#include <cmath>

#include "strata/core/error.h"

namespace strata::localize {

void SessionLocalizationConfig::validate() const {
  localizer.validate();
  fusion.validate();
  if (every < 1) throw InputError("localize: every must be >= 1");
  if (check_frames < 0) throw InputError("localize: check_frames must be >= 0");
}

SessionLocalization localizeSession(const Dataset& frames,
                                    const std::vector<Eigen::Isometry3d>& odometry,
                                    const PriorMap& map, const SessionLocalizationConfig& config,
                                    const SessionProgress& progress) {
  config.validate();
  const std::size_t n = frames.size();
  if (n == 0) throw InputError("localize: the session has no frame");
  if (!odometry.empty() && odometry.size() != n) {
    throw InputError("localize: " + std::to_string(odometry.size()) + " odometry poses for " +
                     std::to_string(n) + " frames");
  }
  std::vector<double> times(n);
  for (std::size_t i = 0; i < n; ++i) {
    times[i] = frames.stamp(i).timestamp_s;
    if (!std::isfinite(times[i]) || (i > 0 && times[i] < times[i - 1]))
      throw InputError("localize: frame " + std::to_string(i) + "'s time is not finite or goes backwards");
    if (!odometry.empty() && !odometry[i].matrix().allFinite())
      throw InputError("localize: odometry pose of frame " + std::to_string(i) + " is not finite");
  }
  const Localizer localizer(map, config.localizer);
  const CameraIntrinsics intrinsics = frames.intrinsics();
  SessionLocalization out;
  out.with_odometry = !odometry.empty();

  // The up-front sample: does the map show this place at all?
  if (config.check_frames > 0) {
    const std::size_t count = std::min<std::size_t>(static_cast<std::size_t>(config.check_frames), n);
    for (std::size_t j = 0; j < count; ++j) {
      const std::size_t i = (2 * j + 1) * n / (2 * count);
      const RgbdFrame frame = frames.load(i);
      const Localization l = localizer.localize(frame.color, frame.depth, intrinsics);
      out.check_localized += l.localized ? 1 : 0;
      ++out.check_frames;
      if (out.check_localized > 0) break;  // one is enough to go on
    }
    if (out.check_localized == 0) {
      throw InputError("the map does not show this session's place: none of " +
                       std::to_string(out.check_frames) +
                       " frames spread over the session localised against it (a map of "
                       "another place?)");
    }
  }

  PoseFusion fusion(config.fusion);
  std::optional<PosePrior> last_localized;
  for (std::size_t i = 0; i < n; ++i) {
    FrameLocalization record;
    record.frame = i;
    record.timestamp_s = times[i];
    if (out.with_odometry) record.fused = fusion.predict(times[i], odometry[i]);
    const bool attempt = i % static_cast<std::size_t>(config.every) == 0;
    if (attempt) {
      const RgbdFrame frame = frames.load(i);
      const std::optional<PosePrior> prior = out.with_odometry ? fusion.prior() : last_localized;
      record.attempted = true;
      record.localization = localizer.localize(frame.color, frame.depth, intrinsics, prior);
      ++out.attempted;
      if (record.localization.localized) ++out.localized;
      if (out.with_odometry) {
        const std::size_t rejected_before = fusion.rejected();
        record.fused = fusion.correct(record.localization);
        if (fusion.rejected() > rejected_before) ++out.rejected;
      } else if (record.localization.localized) {
        record.fused.status = FusionStatus::kCorrected;
        record.fused.T_W_C = record.localization.T_W_C;
        last_localized = PosePrior{record.localization.T_W_C};
      } else {
        record.fused.note = "not localised: " + record.localization.reason;
      }
    }
    out.frames.push_back(std::move(record));
    if (progress && !progress(i + 1, n)) break;
  }
  out.accepted = out.with_odometry ? fusion.accepted() : out.localized;
  return out;
}

}  // namespace strata::localize
