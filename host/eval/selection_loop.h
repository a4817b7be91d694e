#pragma once
// The incremental reconstruction loop of keyframe selection on simulated sessions: the first session is fused
// completely (and, with automatic thresholds, scored against its own reconstruction); every later
// session is scored against the map built so far, its keyframes selected, and only the selected
// ones fused (incremental) or all of them (complete, the comparison). Optionally computes the
// ground truth of every keyframe and scores it with the host reference too.
// Thread safety: not thread safe.
#include <functional>
#include <memory>
#include <vector>

#include "integrate/device_fusion.h"
#include "select/change_support.h"
#include "select/confirmed_points.h"
#include "select/keyframe_scorer.h"
#include "select/keyframe_selection.h"
#include "eval/map_history.h"
#include "eval/selection_truth.h"
#include "sim/session/sim_session.h"

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
  /// Compute KeyframeTruth for keyframes of sessions >= 1 and keep the true surface points of every
  /// keyframe for mapCoverage().
  bool with_truth = false;
  /// Also score every keyframe with the host reference (scoreKeyframeReference).
  bool with_reference = false;
  TruthConfig truth;
  /// Views of vacated places for change detection, added to the selection of sessions >= 1
  /// (views 0: none; demoLoopConfig: 3, the demo's change detector's min weight).
  SupportConfig support{0};
  /// Incremental, sessions >= 1: keep the points the session's keyframes confirmed
  /// (SessionRun::confirmed; off by default, on in demoLoopConfig).
  ConfirmConfig confirm;
  /// Incremental, sessions >= 1: keep the skipped keyframes' samples that disagree with the map,
  /// vacated and arrived (SessionRun::changed_views; off by default, on in demoLoopConfig).
  bool keep_changed_views = false;
  /// ... with the keyframe's depth where the place around each can project (its cell_px is
  /// taken from scorer.sample_stride_px: freeSpace()).
  change::FreeSpaceConfig free_space;
  /// ... and each skipped keyframe also takes the other keyframes' vacated samples it looks
  /// through (shareVacatedPlaces).
  bool share_vacated_places = true;
};

/// config.free_space with the sample grid's cells.
change::FreeSpaceConfig freeSpace(const LoopConfig& config);

struct SessionRun {
  int session = 0;
  std::vector<KeyframeScore> scores;            // device; session 0: against its own map
  std::vector<KeyframeScore> reference_scores;  // with_reference
  std::vector<SampleRaycast> device_samples;    // with_reference: to compare hit masks
  std::vector<SampleRaycast> reference_samples;
  std::vector<KeyframeTruth> truth;  // with_truth, sessions >= 1
  TrajectorySelection selection;     // sessions >= 1
  /// Incremental, sessions >= 1: the counts of the views-of-vacated-places step (its added flags
  /// are selection.support).
  SupportResult support;
  std::vector<std::uint8_t> fused;  // keyframes fused into the map
  /// Incremental with confirm.enabled, sessions >= 1: the confirmed points of every keyframe, for
  /// change detection to carry observations forward (change/carry_forward.h). Fused keyframes'
  /// points count too: one or two fused frames of a place leave it below the detector's min
  /// weight, where the latest observation is the better value (office: printer in session 2,
  /// 0.00 -> 0.43 of it found).
  std::vector<change::ConfirmedPoint> confirmed;
  /// Incremental with keep_changed_views, sessions >= 1, one per skipped keyframe, in order: its
  /// samples that disagree with the map (change/carry_free.h integrates what they saw).
  std::vector<change::ChangedView> changed_views;
  std::size_t shared_vacated_samples = 0;  // of them, taken from other keyframes
  double score_device_ms = 0.0;            // raycast device time, summed
  std::size_t fusedCount() const;
};

/// The loop as `strata demo --incremental` and its tests run it on simulated sessions: a 5 cm
/// selection map (scoring needs the map's shape, not its detail) with constant weights and free
/// space carved (later sessions see removed objects go), truth, and the host reference on the
/// complete run. Keyframes there are sparse (60 per session, ~2.8 s apart): neighbours share
/// little of the view, so the method's moving average over 5 of them spread one keyframe's new
/// space over ~14 s of path and its dilation added more (office, sessions 1-4: 91.8/57.4/65.0 %
/// recall/precision/accuracy with window 5 and dilation 1); this config scores each keyframe on
/// its own (window 1, dilation 0). The library's defaults stay the method's, for keyframe streams
/// whose neighbours overlap.
LoopConfig demoLoopConfig(bool incremental);

class SelectionLoop {
 public:
  /// `context` must outlive the loop. Validates the configs.
  SelectionLoop(vk::Context& context, const LoopConfig& config);

  /// Runs one session (the first call is the first session). `progress(done)` after each keyframe
  /// step (every keyframe is stepped twice: scored, then fused or skipped).
  const SessionRun& addSession(const sim::SimSessionDataset& session,
                               const std::function<void(std::size_t)>& progress = {});

  const std::vector<SessionRun>& sessions() const { return sessions_; }
  const Thresholds& thresholds() const { return thresholds_; }
  /// The thresholds the reference scores of the first session give (with_reference).
  const Thresholds& referenceThresholds() const { return reference_thresholds_; }
  /// Share of the true surface points seen by every keyframe so far that the map has observed
  /// (with_truth).
  SurfaceCoverage mapCoverage();
  DeviceFusion& fusion() { return fusion_; }
  const LoopConfig& config() const { return config_; }

 private:
  /// Scores every keyframe. With `collect_points`, also appends every keyframe's confirmed points
  /// to run.confirmed (when confirm is on), keeps its changed samples (keep_changed_views) and
  /// returns its vacated points (when support views are on; change_support.h), else nothing.
  std::vector<std::vector<Eigen::Vector3f>> scoreSession(
      const sim::SimSessionDataset& session, const std::vector<RgbdFrame>& frames, SessionRun& run,
      bool collect_points, const std::function<void(std::size_t)>& progress);
  void recordTruth(const sim::SimSessionDataset& session, std::size_t index,
                   const sim::SimulatedFrame& frame, const TsdfMap& map, SessionRun& run);
  /// After a session's fusion: its world and what its fused keyframes saw join history_.
  void recordHistory(const sim::SimSessionDataset& session, const SessionRun& run);

  LoopConfig config_;
  DeviceFusion fusion_;
  KeyframeScorer scorer_;
  Thresholds thresholds_;
  Thresholds reference_thresholds_;
  std::vector<SessionRun> sessions_;
  // True surface points of every keyframe of the finished sessions (recordHistory adds them).
  std::vector<Eigen::Vector3f> seen_points_W_;
  // This session's keyframes' true surface points, until their fusion is decided.
  std::vector<std::vector<Eigen::Vector3f>> session_surface_W_;
  MapHistory history_;  // the worlds and fused views the map was built from
};

}  // namespace strata::selection
