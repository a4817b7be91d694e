#include "cli/select_incremental.h"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>

#include "strata/mapper/session_diff.h"
#include "strata/core/progress.h"
#include "cli/select_outputs.h"
#include "cli/select_plot.h"
#include "strata/io/image_io.h"

namespace strata::apps {
namespace {

using Sessions = std::vector<std::unique_ptr<change::RecordingSession>>;

/// Some frames of a dataset, in order.
class SubsetDataset : public Dataset {
 public:
  SubsetDataset(const Dataset& base, std::vector<std::size_t> indices)
      : base_(base), indices_(std::move(indices)) {}
  std::string name() const override { return base_.name() + " (selected keyframes)"; }
  std::size_t size() const override { return indices_.size(); }
  CameraIntrinsics intrinsics() const override { return base_.intrinsics(); }
  RgbdFrame load(std::size_t index) const override { return base_.load(indices_.at(index)); }

 private:
  const Dataset& base_;
  std::vector<std::size_t> indices_;
};

std::vector<std::size_t> indicesOf(const std::vector<std::uint8_t>& fused) {
  std::vector<std::size_t> out;
  for (std::size_t i = 0; i < fused.size(); ++i) {
    if (fused[i]) out.push_back(i);
  }
  return out;
}

/// Change detection on the fused keyframes of every session. Before each session ends, its layer
/// takes the free space its skipped keyframes saw through vacated places (options.free_space,
/// change/skipped_keyframe_evidence.h), then the latest observations around the points its keyframes confirmed
/// (options.carry_forward, change/carry_forward.h), never where it took free space.
change::WorldEvaluation detectOnSelected(vk::Context& context, const sim::World& world,
                                         const Sessions& sessions, const MapConfig& change_map,
                                         const DiffRunInfo& info,
                                         const selection::SelectionLoop& loop,
                                         const IncrementalOptions& options, bool quiet,
                                         IncrementalResult& r) {
  std::vector<SubsetDataset> subsets;
  std::size_t total = 0, done = 0;
  for (std::size_t s = 0; s < sessions.size(); ++s) {
    subsets.emplace_back(sessions[s]->session(), indicesOf(loop.sessions()[s].fused));
    total += subsets.back().size();
  }
  DiffPipeline pipeline(context, change_map, info.change, info.objects);
  const float min_weight = info.change.min_weight;
  const change::FreeSpaceConfig free_config = selection::freeSpace(loop.config());
  TsdfMap latest(change_map);  // per voxel, the last session that observed it
  // One download per session: the layer is edited, then (as ended: endSession leaves a session's
  // layer as it is) kept as the latest observations for the sessions after it.
  const auto before_end = [&](change::ChangeDetector& detector, int session) {
    TsdfMap layer = detector.sessionMap(session);
    if (session > 0 && (options.free_space || options.carry_forward)) {
      const selection::SessionRun& run = loop.sessions()[session];
      change::VoxelSet own;
      if (options.free_space) {
        const CameraIntrinsics& camera = sessions[session]->session().intrinsics();
        const auto start = std::chrono::steady_clock::now();
        const change::FreeSpaceStats stats = change::integrateChangedPlaces(
            run.changed_views, camera, free_config, latest, layer, nullptr, &own);
        r.free_space_s +=
            std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        r.free_space_pixels +=
            stats.views * static_cast<std::size_t>(camera.width_px) * camera.height_px;
        r.free_space.views += stats.views;
        r.free_space.samples += stats.samples;
        r.free_space.voxels += stats.voxels;
        r.free_space.free_voxels += stats.free_voxels;
        r.free_space.arrived_samples += stats.arrived_samples;
        r.free_space.depth_pixels += stats.depth_pixels;
        r.free_space_shared_samples += run.shared_vacated_samples;
      }
      if (options.carry_forward) {
        const change::CarryStats stats =
            change::carryObserved(latest, run.confirmed, min_weight, layer, &own);
        r.carried.points += stats.points;
        r.carried.voxels += stats.voxels;
      }
      detector.replaceSessionMap(session, layer);
    }
    change::keepLatestObserved(layer, min_weight, latest);
  };
  ProgressBar progress("change detection on selected keyframes", total, !quiet);
  for (const auto& subset : subsets) {
    pipeline.addSession(subset, subset.name(), progress, done, before_end);
  }
  progress.finish();
  const DiffResult result = pipeline.finish();
  std::vector<std::vector<change::DiscoveredObject>> objects;
  std::vector<const change::VisibleSurface*> seen;
  for (std::size_t s = 0; s < sessions.size(); ++s) {
    objects.push_back(result.sessions[s].objects);
    seen.push_back(&sessions[s]->seen());  // what every keyframe saw: the same truth as complete
  }
  change::EvaluationConfig eval_config;
  eval_config.min_views = info.change.minFrames();
  return change::evaluateWorld(world, objects, result.static_mesh, seen, eval_config);
}

/// Every evaluated moved object of `complete` with its match in `incremental` (both evaluate the
/// same truth, so the same objects).
std::vector<InstanceOutcome> instanceOutcomes(const sim::World& world,
                                              const change::WorldEvaluation& complete,
                                              const change::WorldEvaluation& incremental) {
  std::vector<InstanceOutcome> out;
  for (std::size_t s = 0; s < complete.sessions.size(); ++s) {
    for (const change::ObjectMatch& c : complete.sessions[s].objects) {
      if (!c.evaluated) continue;
      InstanceOutcome o;
      o.session = static_cast<int>(s);
      o.object_id = c.object_id;
      o.name = c.name;
      o.arrival = change::isArrival(world, o.session, c.object_id);
      o.complete = c;
      for (const change::ObjectMatch& i : incremental.sessions.at(s).objects) {
        if (i.object_id == c.object_id) o.incremental = i;
      }
      out.push_back(std::move(o));
    }
  }
  return out;
}

/// Per session: the plot of the metrics along the trajectory with the selected and
/// the truly positive keyframes, and the same as CSV (metrics, decisions, true pixel shares).
void writeSessionFiles(const selection::SelectionLoop& loop, const selection::LoopTruth& loop_truth,
                       const Sessions& sessions, const std::string& out_dir,
                       std::vector<std::string>& files) {
  selection::SelectionConfig config = loop.config().selection;
  config.thresholds = loop.thresholds();
  for (const auto& run : loop.sessions()) {
    // Session 0 was scored against its own map: its file shows where the automatic thresholds
    // come from (its decisions are what they would be; all of it was fused).
    const selection::TrajectorySelection selection =
        run.session == 0 ? selection::selectKeyframes(run.scores, config) : run.selection;
    const std::filesystem::path stem =
        std::filesystem::path(out_dir) / ("select_session_" + std::to_string(run.session));
    std::vector<std::uint8_t> truth;
    std::vector<ScoredKeyframe> keyframes(run.scores.size());
    for (std::size_t i = 0; i < run.scores.size(); ++i) {
      keyframes[i].name = "keyframe_" + std::to_string(i);
      keyframes[i].timestamp_s = sessions.at(run.session)->session().timestamp(i);
      keyframes[i].score = run.scores[i];
    }
    const std::vector<selection::KeyframeTruth>& run_truth = loop_truth.truth(run.session);
    for (const auto& t : run_truth) truth.push_back(t.positive ? 1 : 0);
    writeColorPng(stem.string() + ".png", renderSelectionPlot(selection, config, truth));
    writeSelectionCsv(stem.string() + ".csv", keyframes, selection, run_truth);
    files.push_back(stem.string() + ".png");
    files.push_back(stem.string() + ".csv");
  }
}

}  // namespace

IncrementalResult runIncremental(vk::Context& context, const sim::World& world,
                                 const Sessions& sessions, const MapConfig& change_map,
                                 const DiffRunInfo& info, const change::WorldEvaluation& complete,
                                 const std::string& out_dir, bool quiet,
                                 const IncrementalOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  const auto configured = [&options](bool incremental) {
    selection::LoopConfig c = selection::demoLoopConfig(incremental);
    c.selection.smoothing_window = options.smoothing_window;
    c.selection.dilation = options.dilation;
    c.confirm.enabled = incremental && options.carry_forward;
    c.keep_changed_views = incremental && options.free_space;
    c.free_space.place_radius_m = options.free_space_radius_m;
    c.share_vacated_places = options.free_space_shared;
    c.free_space.arrived_ring_cells = options.arrived_ring_cells;
    return c;
  };
  selection::SelectionLoop full(context, configured(false));
  selection::SelectionLoop incremental(context, configured(true));
  selection::LoopTruth full_truth, incremental_truth;
  std::size_t total = 0, done = 0;
  for (const auto& s : sessions) total += 4 * s->size();
  ProgressBar progress("keyframe selection: complete + incremental", total, !quiet);
  for (const auto& s : sessions) {
    for (auto [loop, truth] : {std::pair{&full, &full_truth}, {&incremental, &incremental_truth}}) {
      const std::size_t offset = done;
      truth->addSession(*loop, s->session(), [&](std::size_t k) { progress.update(offset + k); });
      done += 2 * s->size();
    }
  }
  progress.finish();
  IncrementalResult r;
  r.thresholds = full.thresholds();
  r.methods = selection::evaluateMethods(full, full_truth);
  r.agreement = selection::deviceReferenceAgreement(full);
  r.images = selection::imagesAfterFirstSession(incremental);
  r.images_per_session = selection::imagesPerSession(incremental);
  for (const selection::SessionRun& run : incremental.sessions()) {
    if (run.session == 0) continue;
    r.fused_confusion.add(selection::confusion(run.fused, incremental_truth.truth(run.session)));
  }
  r.coverage_complete = full_truth.mapCoverage(full).ratio();
  r.coverage_incremental = incremental_truth.mapCoverage(incremental).ratio();
  writeSessionFiles(incremental, incremental_truth, sessions, out_dir, r.files);
  r.objects_complete = complete.totals;
  r.arrivals_complete = change::arrivalCounts(world, complete);
  const change::WorldEvaluation on_selected =
      detectOnSelected(context, world, sessions, change_map, info, incremental, options, quiet, r);
  r.objects_incremental = on_selected.totals;
  r.arrivals_incremental = change::arrivalCounts(world, on_selected);
  r.instances = instanceOutcomes(world, complete, on_selected);
  r.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return r;
}

std::string summarizeIncremental(const IncrementalResult& r) {
  char text[2000];
  const selection::Confusion& ours = r.methods[0].confusion;
  const selection::Confusion& ncc = r.methods[1].confusion;
  const selection::Confusion& hist = r.methods[2].confusion;
  std::string per_session;
  for (const selection::ImageUse& use : r.images_per_session) {
    per_session +=
        (per_session.empty() ? "" : "/") + std::to_string(std::lround(100 * use.share()));
  }
  std::snprintf(
      text, sizeof(text),
      "Keyframe selection (recall/precision/accuracy against the simulator's truth, sessions 1+): "
      "reprojection %.1f/%.1f/%.1f %%, NCC %.1f/%.1f/%.1f %%, histogram %.1f/%.1f/%.1f %%; device and "
      "reference hit masks agree on %.3f %% of samples, surface checks on %.3f %%, %zu decisions "
      "differ. Incremental: fused "
      "%zu of %zu keyframes after the first session (%.1f %%; per session %s %%; fused keyframes against the truth: %s), surface coverage %.2f %% vs "
      "%.2f %% fusing all; change detection on the fused keyframes (%zu voxels carried forward "
      "around %zu points the keyframes confirmed; free space from %zu vacated samples of %zu "
      "skipped keyframes, %zu of those samples shared among keyframes, and surfaces from %zu "
      "arrived samples, with %.3g %% of their depth pixels) found %zu of %zu moved "
      "objects (all keyframes: %zu of %zu); counting each moved object only in the sessions in "
      "which it changed, %zu of %zu (all keyframes: %zu of %zu). %.1f s.",
      100 * ours.recall(), 100 * ours.precision(), 100 * ours.accuracy(), 100 * ncc.recall(),
      100 * ncc.precision(), 100 * ncc.accuracy(), 100 * hist.recall(), 100 * hist.precision(),
      100 * hist.accuracy(), 100 * r.agreement.hitAgreement(), 100 * r.agreement.surfaceAgreement(),
      r.agreement.decision_mismatches, r.images.fused, r.images.total, 100 * r.images.share(),
      per_session.c_str(), r.fused_confusion.describe().c_str(),
      100 * r.coverage_incremental, 100 * r.coverage_complete, r.carried.voxels, r.carried.points,
      r.free_space.samples, r.free_space.views, r.free_space_shared_samples,
      r.free_space.arrived_samples,
      r.free_space_pixels > 0 ? 100.0 * r.free_space.depth_pixels / r.free_space_pixels : 0.0,
      r.objects_incremental.found, r.objects_incremental.moved, r.objects_complete.found,
      r.objects_complete.moved, r.arrivals_incremental.found, r.arrivals_incremental.arrivals,
      r.arrivals_complete.found, r.arrivals_complete.arrivals, r.wall_s);
  return text;
}

}  // namespace strata::apps
