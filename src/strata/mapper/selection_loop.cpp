#include "strata/mapper/selection_loop.h"

#include <algorithm>

#include "strata/raycast/tsdf_sampling.h"

namespace strata::selection {
namespace {

MapperConfig loopMapperConfig(const LoopConfig& config) {
  MapperConfig c;
  c.map = config.map;
  c.keyframe_scoring = true;
  c.scorer = config.scorer;
  return c;
}

}  // namespace

void LoopConfig::validate() const {
  selection.validate();
  changed_views.validate();
  confirm.validate();
}

change::FreeSpaceConfig freeSpace(const LoopConfig& config) {
  change::FreeSpaceConfig c = config.free_space;
  c.cell_px = config.scorer.sample_stride_px;
  return c;
}

std::size_t SessionRun::fusedCount() const {
  return static_cast<std::size_t>(std::count(fused.begin(), fused.end(), 1));
}

SelectionLoop::SelectionLoop(vk::Context& context, const LoopConfig& config)
    : config_(config),
      mapper_(loopMapperConfig(config), context),
      thresholds_(config.selection.thresholds),
      reference_thresholds_(config.selection.thresholds) {
  config_.validate();
}

void SelectionLoop::scoreSession(const std::vector<RgbdFrame>& frames,
                                 const CameraIntrinsics& intrinsics, SessionRun& run,
                                 bool collect_points,
                                 const std::function<void(std::size_t)>& progress) {
  TsdfMap map(config_.map);
  if (config_.with_reference) map = mapper_.download();
  for (std::size_t i = 0; i < frames.size(); ++i) {
    SampleRaycast samples;
    const KeyframeDecision decision = mapper_.scoreKeyframe(frames[i], intrinsics, &samples);
    run.scores.push_back(decision.score);
    run.score_device_ms += decision.device_ms;
    if (collect_points && config_.keep_changed_views) {
      run.changed_views.push_back(changedView(samples, frames[i], config_.changed_views));
    }
    if (collect_points && config_.confirm.enabled) {
      const auto confirmed = confirmedPoints(samples, frames[i], intrinsics, config_.confirm);
      run.confirmed.insert(run.confirmed.end(), confirmed.begin(), confirmed.end());
    }
    if (config_.with_reference) {
      SampleRaycast reference;
      run.reference_scores.push_back(
          scoreKeyframeReference(map, frames[i], intrinsics, config_.scorer, &reference));
      run.device_samples.push_back(std::move(samples));
      run.reference_samples.push_back(std::move(reference));
    }
    if (progress) progress(i + 1);
  }
}

void SelectionLoop::keepSkippedViews(const std::vector<RgbdFrame>& frames,
                                     const CameraIntrinsics& intrinsics, SessionRun& run) const {
  // Only the skipped keyframes' vacated samples are wanted: a fused keyframe gives its own. Their
  // depth is kept once, around their own and shared samples.
  const std::size_t n = frames.size();
  std::vector<std::uint8_t> skipped_flags(n);
  for (std::size_t i = 0; i < n; ++i) skipped_flags[i] = run.fused[i] ? 0 : 1;
  if (config_.share_vacated_places) {
    run.shared_vacated_samples =
        shareVacatedPlaces(run.changed_views, frames, skipped_flags, intrinsics,
                           config_.changed_views, config_.scorer.sample_stride_px);
  }
  std::vector<change::ChangedView> skipped;
  for (std::size_t i = 0; i < n; ++i) {
    if (!skipped_flags[i]) continue;
    change::keepDepthAround(frames[i].depth, intrinsics, freeSpace(config_),
                            run.changed_views[i]);
    skipped.push_back(std::move(run.changed_views[i]));
  }
  run.changed_views = std::move(skipped);
}

const SessionRun& SelectionLoop::addSession(const Dataset& session, LoopObserver* observer,
                                            const std::function<void(std::size_t)>& progress) {
  SessionRun run;
  run.session = static_cast<int>(sessions_.size());
  const std::size_t n = session.size();
  const CameraIntrinsics intrinsics = session.intrinsics();
  if (observer != nullptr) {
    // Truth is judged against the map as it was before this session.
    const TsdfMap before = observer->wantsMapBefore() ? mapper_.download() : TsdfMap(config_.map);
    observer->sessionStarted(run.session, before);
  }
  std::vector<RgbdFrame> frames;
  frames.reserve(n);
  for (std::size_t i = 0; i < n; ++i) {
    frames.push_back(session.load(i));
    if (observer != nullptr) observer->frameLoaded(i, frames.back());
  }
  const auto step = [&](std::size_t offset) {
    return [&, offset](std::size_t done) {
      if (progress) progress(offset + done);
    };
  };
  if (run.session > 0) {
    // The complete run fuses every keyframe anyway: nothing skipped, no points to keep.
    scoreSession(frames, intrinsics, run, config_.incremental, step(0));
    SelectionConfig selection = config_.selection;
    selection.thresholds = thresholds_;
    run.selection = selectKeyframes(run.scores, selection);
  }
  const bool fuse_all = run.session == 0 || !config_.incremental;
  run.fused = fuse_all ? std::vector<std::uint8_t>(n, 1) : run.selection.selected;
  if (!run.changed_views.empty()) keepSkippedViews(frames, intrinsics, run);
  for (std::size_t i = 0; i < n; ++i) {
    if (run.fused[i]) mapper_.integrate(frames[i], intrinsics);
    if (progress) progress(n + i + 1);
  }
  if (run.session == 0) {
    scoreSession(frames, intrinsics, run, false, {});
    if (config_.auto_thresholds) {
      const int window = config_.selection.smoothing_window;
      thresholds_ = autoThresholds(run.scores, window, config_.selection.thresholds);
      if (config_.with_reference) {
        reference_thresholds_ =
            autoThresholds(run.reference_scores, window, config_.selection.thresholds);
      }
    }
  }
  if (observer != nullptr) observer->sessionEnded(run);
  sessions_.push_back(std::move(run));
  return sessions_.back();
}

}  // namespace strata::selection
