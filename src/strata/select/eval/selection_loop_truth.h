#pragma once
// Ground truth of the keyframe-selection loop (mapper/selection_loop.h) on simulated sessions:
// the simulator's truth for every keyframe of sessions >= 1 against the map before the session
// (selection_truth.h), and the share of the true surface every keyframe saw that the map observed.
// Also the loop configuration `strata demo --incremental` and its tests run on simulated sessions.
// Thread safety: not thread safe.
#include <functional>
#include <memory>
#include <vector>

#include "strata/select/eval/map_history.h"
#include "strata/select/eval/selection_truth.h"
#include "strata/mapper/selection_loop.h"
#include "strata/sim/session/sim_session.h"

namespace strata::selection {

/// The loop on simulated sessions: a 5 cm selection map (scoring needs the map's shape, not its
/// detail) with constant weights and free space carved (later sessions see removed objects go),
/// the host reference on the complete run, and on the incremental run the confirmed points and
/// changed views change detection carries forward. Keyframes there are sparse (60 per session,
/// ~2.8 s apart): neighbours share little of the view, so each keyframe is scored on its own
/// (window 1, dilation 0; docs/select.md says why). The library's defaults stay the
/// method's, for keyframe streams whose neighbours overlap.
LoopConfig demoLoopConfig(bool incremental);

/// Records the truth while a SelectionLoop runs simulated sessions.
class LoopTruth : public LoopObserver {
 public:
  explicit LoopTruth(const TruthConfig& config = {});

  /// Runs `session` (the next one) through `loop`, recording its truth; one LoopTruth per loop.
  const SessionRun& addSession(SelectionLoop& loop, const sim::SimSessionDataset& session,
                               const std::function<void(std::size_t)>& progress = {});

  /// Per keyframe of session `session` (empty for session 0, which has no map before it).
  const std::vector<KeyframeTruth>& truth(int session) const;
  /// Share of the true surface points seen by every keyframe so far that the loop's map observed.
  SurfaceCoverage mapCoverage(SelectionLoop& loop) const;

  bool wantsMapBefore() const override { return !truth_.empty(); }
  void sessionStarted(int session, const TsdfMap& map_before) override;
  void frameLoaded(std::size_t index, const RgbdFrame& frame) override;
  void sessionEnded(const SessionRun& run) override;

 private:
  class RenderedSession;

  TruthConfig config_;
  const sim::SimSessionDataset* session_ = nullptr;  // during addSession
  const RenderedSession* rendered_ = nullptr;        // its frames, as the loop loads them
  std::unique_ptr<TsdfMap> map_before_;  // sessions >= 1, during addSession
  std::vector<std::vector<KeyframeTruth>> truth_;  // per session
  // True surface points of every keyframe of the finished sessions (sessionEnded adds them).
  std::vector<Eigen::Vector3f> seen_points_W_;
  // This session's keyframes' true surface points, until their fusion is decided.
  std::vector<std::vector<Eigen::Vector3f>> session_surface_W_;
  MapHistory history_;  // the worlds and fused views the map was built from
};

}  // namespace strata::selection
