#pragma once
// The incremental loop of keyframe selection inside `strata demo --incremental`: for each new session, select
// its keyframes against the map built so far, fuse only the selected ones, and compare with fusing
// everything: images used, surface coverage, keyframe-selection scores against the simulator's
// truth (reprojection, NCC, histogram), device-vs-reference agreement, and change detection run
// on the selected keyframes only against the demo's complete run.
#include <memory>
#include <string>
#include <vector>

#include "cli/diff_report.h"
#include "strata/change/carry_forward.h"
#include "strata/change/eval/evaluation_session.h"
#include "strata/change/eval/evaluation_world.h"
#include "strata/select/eval/selection_loop_truth.h"
#include "strata/select/eval/selection_report.h"

namespace strata::apps {

/// One evaluated moved object in one session, as both change detections found it.
struct InstanceOutcome {
  int session = 0;
  int object_id = 0;
  std::string name;
  bool arrival = false;  // it changed since the session before
  change::ObjectMatch complete;
  change::ObjectMatch incremental;
};

struct IncrementalResult {
  selection::Thresholds thresholds;
  std::vector<selection::MethodResult> methods;  // reproj, ncc, hist
  selection::DeviceReferenceAgreement agreement;
  selection::ImageUse images;                           // keyframes fused after the first session
  std::vector<selection::ImageUse> images_per_session;  // ... per session, 1 on
  /// Observations carried forward into the sessions' change-detection layers around the points
  /// the keyframes confirmed (change/carry_forward.h), over the sessions.
  change::CarryStats carried;
  /// Free space the skipped keyframes saw through vacated places, integrated into the sessions'
  /// change-detection layers from their vacated samples (change/skipped_keyframe_evidence.h),
  /// over the sessions; free_space_pixels: all pixels of those keyframes, to put the depth kept in proportion.
  change::FreeSpaceStats free_space;
  std::size_t free_space_pixels = 0;
  std::size_t free_space_shared_samples = 0;  // of free_space.samples, shared among keyframes
  double free_space_s = 0.0;  // wall time of integrating them (change::integrateChangedPlaces)
  /// The fused keyframes (selected or added) against the truth.
  selection::Confusion fused_confusion;
  double coverage_complete = 0.0;         // surface coverage of the map fused from every keyframe
  double coverage_incremental = 0.0;      // ... from the selected ones
  change::ObjectCounts objects_complete;  // the demo's change detection (every keyframe)
  change::ObjectCounts objects_incremental;  // ... on the selected keyframes
  /// The same over the objects' arrivals only (change/evaluation_world.h): the sessions in which
  /// each moved object changed. Selection skips the images of an object standing as before, so
  /// its instances in those sessions are what the two runs may differ in by design.
  change::ArrivalCounts arrivals_complete;
  change::ArrivalCounts arrivals_incremental;
  std::vector<InstanceOutcome> instances;  // every evaluated moved object, session by session
  std::vector<std::string> files;
  double wall_s = 0.0;
};

/// Smoothing and dilation of the demo's selection (selection::demoLoopConfig's by default).
struct IncrementalOptions {
  int smoothing_window = selection::demoLoopConfig(true).selection.smoothing_window;
  int dilation = selection::demoLoopConfig(true).selection.dilation;
  /// Carry the latest observations forward where keyframes confirmed the map, so change
  /// detection sees objects standing as before (change/carry_forward.h).
  bool carry_forward = true;
  /// Integrate what skipped keyframes saw change into change detection: the free space through
  /// vacated places, from their vacated samples, and arrived surfaces
  /// (change/skipped_keyframe_evidence.h).
  bool free_space = true;
  /// ... in the place within this radius of each vacated sample (metres).
  float free_space_radius_m = change::FreeSpaceConfig{}.place_radius_m;
  /// ... also from the vacated places other keyframes found (selection::shareVacatedPlaces).
  bool free_space_shared = true;
  /// ... arrived surfaces: cells of depth kept around each arrived sample's, on each side (0: no
  /// arrivals, free space only).
  int arrived_ring_cells = change::FreeSpaceConfig{}.arrived_ring_cells;
};

/// `sessions`: the demo's sessions, already fused by its complete run (their seen() surfaces are
/// the truth both change detections are scored against); `complete`: that run's evaluation.
/// A bad window or dilation throws InputError.
IncrementalResult runIncremental(
    vk::Context& context, const sim::World& world,
    const std::vector<std::unique_ptr<change::RecordingSession>>& sessions,
    const MapConfig& change_map, const DiffRunInfo& info, const change::WorldEvaluation& complete,
    const std::string& out_dir, bool quiet, const IncrementalOptions& options = {});

/// A few sentences for the demo's closing paragraph.
std::string summarizeIncremental(const IncrementalResult& result);
/// The same figures as one JSON object (report.json's "incremental").
std::string incrementalJson(const IncrementalResult& result);

}  // namespace strata::apps
