#pragma once
// The incremental reconstruction loop of keyframe selection, on a Mapper: the first session is
// fused completely (and, with automatic thresholds, scored against its own reconstruction to set
// the thresholds); every later session is scored against the map built so far, its keyframes
// selected, and only the selected ones fused (incremental) or all of them (complete, the
// comparison). Sessions are any Dataset (frames with their poses, in the map's world frame).
// A LoopObserver sees every session's frames and runs: evaluation against ground truth
// (eval/selection_truth_recorder.h) is one, and nothing here depends on it.
// Errors: bad configs throw InputError from the constructor; bad frames InputError from
// addSession (before anything of that frame is fused).
// Thread safety: not thread safe.
#include <functional>
#include <memory>
#include <vector>

#include "strata/change/skipped_keyframe_evidence.h"
#include "strata/core/dataset.h"
#include "strata/mapper/mapper.h"
#include "strata/select/changed_views.h"
#include "strata/select/confirmed_points.h"
#include "strata/select/keyframe_scorer.h"
#include "strata/select/keyframe_selection.h"

namespace strata::selection {

struct LoopConfig {
  /// The map keyframes are scored against and fused into.
  MapConfig map;
  ScorerConfig scorer;
  /// Method, smoothing, dilation; its thresholds are used unless auto_thresholds.
  SelectionConfig selection;
  bool auto_thresholds = true;
  /// Fuse only the selected keyframes of sessions after the first (false: fuse all: the complete
  /// map the incremental one is compared with).
  bool incremental = true;
  /// Also score every keyframe with the host reference (scoreKeyframeReference).
  bool with_reference = false;
  /// Incremental, sessions >= 1: keep the points the session's keyframes confirmed
  /// (SessionRun::confirmed; off by default).
  ConfirmConfig confirm;
  /// Incremental, sessions >= 1: keep the skipped keyframes' samples that disagree with the map,
  /// vacated and arrived (SessionRun::changed_views; off by default).
  bool keep_changed_views = false;
  /// ... with these tolerances (select/changed_views.h) ...
  ChangedViewConfig changed_views;
  /// ... and the keyframe's depth where the place around each can project (its cell_px is
  /// taken from scorer.sample_stride_px: freeSpace()) ...
  change::FreeSpaceConfig free_space;
  /// ... and each skipped keyframe also takes the other keyframes' vacated samples it looks
  /// through (shareVacatedPlaces).
  bool share_vacated_places = true;

  void validate() const;  // InputError naming the field
};

/// config.free_space with the sample grid's cells.
change::FreeSpaceConfig freeSpace(const LoopConfig& config);

struct SessionRun {
  int session = 0;
  std::vector<KeyframeScore> scores;            // device; session 0: against its own map
  std::vector<KeyframeScore> reference_scores;  // with_reference
  std::vector<SampleRaycast> device_samples;    // with_reference: to compare hit masks
  std::vector<SampleRaycast> reference_samples;
  TrajectorySelection selection;     // sessions >= 1
  std::vector<std::uint8_t> fused;  // keyframes fused into the map
  /// Incremental with confirm.enabled, sessions >= 1: the confirmed points of every keyframe, for
  /// change detection to carry observations forward (change/carry_forward.h). Fused keyframes'
  /// points count too: a place that one or two fused frames saw stays below the change detector's
  /// minimum weight, where the latest observation is the better value.
  std::vector<change::ConfirmedPoint> confirmed;
  /// Incremental with keep_changed_views, sessions >= 1, one per skipped keyframe, in order: its
  /// samples that disagree with the map (change/skipped_keyframe_evidence.h integrates what they
  /// saw).
  std::vector<change::ChangedView> changed_views;
  std::size_t shared_vacated_samples = 0;  // of them, taken from other keyframes
  double score_device_ms = 0.0;            // raycast device time, summed
  std::size_t fusedCount() const;
};

/// What a loop shows its observer, in this order per session: sessionStarted, frameLoaded for
/// every frame (index order, each exactly once, right after the loop loaded it), sessionEnded.
class LoopObserver {
 public:
  virtual ~LoopObserver() = default;
  /// Whether sessionStarted needs the map as it was before the session (a device download).
  virtual bool wantsMapBefore() const { return false; }
  /// `map_before`: the map before this session's frames, or an empty map unless wantsMapBefore.
  virtual void sessionStarted(int /*session*/, const TsdfMap& /*map_before*/) {}
  virtual void frameLoaded(std::size_t /*index*/, const RgbdFrame& /*frame*/) {}
  virtual void sessionEnded(const SessionRun& /*run*/) {}
};

class SelectionLoop {
 public:
  /// `context` must outlive the loop. Validates the config.
  SelectionLoop(vk::Context& context, const LoopConfig& config);

  /// Runs one session (the first call is the first session). `progress(done)` after each keyframe
  /// step (every keyframe is stepped twice: scored, then fused or skipped). `observer` optional.
  /// The reference returned is valid until the next addSession.
  const SessionRun& addSession(const Dataset& session, LoopObserver* observer = nullptr,
                               const std::function<void(std::size_t)>& progress = {});

  const std::vector<SessionRun>& sessions() const { return sessions_; }
  const Thresholds& thresholds() const { return thresholds_; }
  /// The thresholds the reference scores of the first session give (with_reference).
  const Thresholds& referenceThresholds() const { return reference_thresholds_; }
  /// Host copy of the map built so far.
  TsdfMap map() { return mapper_.download(); }
  Mapper& mapper() { return mapper_; }
  const LoopConfig& config() const { return config_; }

 private:
  /// Scores every keyframe. With `collect_points`, also appends every keyframe's confirmed points
  /// to run.confirmed (when confirm is on) and keeps its changed samples (keep_changed_views).
  void scoreSession(const std::vector<RgbdFrame>& frames, const CameraIntrinsics& intrinsics,
                    SessionRun& run, bool collect_points,
                    const std::function<void(std::size_t)>& progress);
  /// Keeps only the skipped keyframes' changed views, with their depth around their samples.
  void keepSkippedViews(const std::vector<RgbdFrame>& frames, const CameraIntrinsics& intrinsics,
                        SessionRun& run) const;

  LoopConfig config_;
  Mapper mapper_;
  Thresholds thresholds_;
  Thresholds reference_thresholds_;
  std::vector<SessionRun> sessions_;
};

}  // namespace strata::selection
