#include "cli/fuse_session.h"

#include <sys/resource.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <sstream>

#include "cli/esdf_slice.h"
#include "strata/core/progress.h"
#include "cli/shaded_view.h"
#include "strata/core/atomic_file.h"
#include "strata/core/clock.h"
#include "strata/core/error.h"
#include "strata/io/tum_format.h"
#include "strata/mapper/eval/accuracy.h"
#include "strata/integrate/tsdf_integration.h"
#include "strata/io/image_io.h"
#include "strata/map/map_file.h"
#include "strata/mesh/extract_mesh.h"
#include "strata/mesh/ply.h"
#include "strata/raycast/raycast.h"
#include "strata/sim/analytic_dataset.h"
#include "strata/trajectory/trajectory_error.h"
#include "strata/io/tum_writer.h"

namespace strata::apps {
namespace {

double peakHostMemoryMiB() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return static_cast<double>(usage.ru_maxrss) / 1024.0;  // ru_maxrss is KiB on Linux
}

std::unique_ptr<Dataset> openInput(const FuseOptions& o) {
  if (o.dataset.empty() || o.dataset == "analytic") {
    return std::make_unique<sim::AnalyticDataset>();
  }
  return openDataset(o.dataset, o.dataset_options);
}

}  // namespace

FuseSession::FuseSession(const FuseOptions& options)
    : options_(options), dataset_(openInput(options)), map_(options.map) {
  analytic_ = dynamic_cast<const sim::AnalyticDataset*>(dataset_.get());
  dataset_->intrinsics().validate();
  const std::size_t limit = options_.frames > 0 ? static_cast<std::size_t>(options_.frames)
                                                : dataset_->size();
  for (std::size_t i = 0; i < dataset_->size() && frame_indices_.size() < limit;
       i += static_cast<std::size_t>(options_.stride)) {
    frame_indices_.push_back(i);
  }
  if (frame_indices_.empty()) throw InputError("dataset '" + dataset_->name() + "' has no frames");
  if (!dataset_->warnings().empty()) {
    std::fprintf(stderr, "strata fuse: %s\n", dataset_->warnings().c_str());
  }
  if (!options_.reference) {
    vk::ContextOptions context_options;
    context_options.device_selector = options_.device;
    context_ = vk::Context::create(context_options);
    MapperConfig config;
    config.map = options_.map;
    config.esdf = options_.esdf;  // kept up to date after every frame (incrementally)
    mapper_ = std::make_unique<Mapper>(config, *context_);
  }
}

FuseSession::~FuseSession() = default;

bool FuseSession::fuseFrame(const RgbdFrame& frame) {
  if (options_.track) return trackFrame(frame);
  if (mapper_) {
    const FrameStats stats = mapper_->integrate(frame, dataset_->intrinsics()).fusion;
    totals_.upload_ms += stats.upload_ms;
    totals_.normals_ms += stats.normals_ms;
    totals_.allocate_ms += stats.allocate_ms;
    totals_.integrate_ms += stats.integrate_ms;
    totals_.wall_ms += stats.wall_ms;
    totals_.touched_blocks += stats.touched_blocks;
    if (options_.esdf) updateEsdf();
  } else {
    const auto start = std::chrono::steady_clock::now();
    integrateFrameReference(map_, frame, dataset_->intrinsics());
    reference_ms_ += msSince(start);
  }
  last_pose_ = frame.T_W_C;
  return true;
}

bool FuseSession::trackFrame(const RgbdFrame& frame) {
  const bool first = mapper_->framesIntegrated() == 0 && tracked_ + lost_ == 0;
  const TrackedFrame result = mapper_->trackAndIntegrate(frame, dataset_->intrinsics());
  if (!first) {
    ++tracked_;
    track_wall_ms_ += result.track.wall_ms;
    track_raycast_ms_ += result.track.raycast_ms;
    track_equations_ms_ += result.track.equations_ms;
    track_iterations_ += result.track.iterations;
  }
  if (!result.fused) {
    ++lost_;
    if (first_lost_reason_.empty()) first_lost_reason_ = frame.name + ": " + result.track.reason;
    return false;
  }
  const FrameStats& stats = result.integrate.fusion;
  totals_.upload_ms += stats.upload_ms;
  totals_.normals_ms += stats.normals_ms;
  totals_.allocate_ms += stats.allocate_ms;
  totals_.integrate_ms += stats.integrate_ms;
  totals_.wall_ms += stats.wall_ms;
  totals_.touched_blocks += stats.touched_blocks;
  fusion_wall_ms_ += stats.wall_ms;
  if (options_.esdf) updateEsdf();
  if (!first) track_sigma_m_.push_back(result.track.translation_sigma_m);
  estimate_.push_back({frame.timestamp_s, result.track.T_W_C});
  dataset_poses_.push_back({frame.timestamp_s, frame.T_W_C});
  last_pose_ = result.track.T_W_C;
  return true;
}

bool FuseSession::writeTrajectory() {
  try {
    writeTumTrajectory(options_.trajectory_path, estimate_,
                       {"timestamp tx ty tz qx qy qz qw (camera to world, strata fuse --track)"});
  } catch (const Error& e) {
    std::fprintf(stderr, "strata fuse: the trajectory was not written: %s\n", e.what());
    return false;
  }
  written_.push_back("trajectory " + options_.trajectory_path);
  return true;
}

std::string FuseSession::trackingSummary() const {
  if (!options_.track) return "";
  std::ostringstream s;
  s.precision(2);
  s << std::fixed << " Tracking: " << tracked_ << " frames tracked, " << lost_
    << " lost (not fused)";
  if (!first_lost_reason_.empty()) s << ", first lost " << first_lost_reason_;
  if (tracked_ > 0) {
    const double n = static_cast<double>(tracked_);
    s << "; " << track_wall_ms_ / n << " ms per frame tracking (device time: raycast "
      << track_raycast_ms_ / n << " ms, normal equations " << track_equations_ms_ / n << " ms over "
      << track_iterations_ / n << " iterations)";
  }
  if (!track_sigma_m_.empty()) {
    std::vector<double> sigma = track_sigma_m_;
    std::sort(sigma.begin(), sigma.end());
    s << "; stated uncertainty per frame (worst direction, docs/track.md): median "
      << sigma[sigma.size() / 2] * 1e3 << " mm, largest " << sigma.back() * 1e3 << " mm";
  }
  if (fused_ > 0) {
    s << ", " << fusion_wall_ms_ / static_cast<double>(fused_) << " ms per frame fusion (wall)";
  }
  s << ".";
  if (estimate_.size() >= 3) {
    // NOTE: the dataset's own poses (ignored by tracking after the first frame) as the truth.
    const trajectory::TrajectoryError error =
        trajectory::evaluateTrajectory(estimate_, dataset_poses_, trajectory::Alignment::kSE3);
    s.precision(1);
    s << " ATE against the dataset's poses (SE(3) aligned, " << error.matched << " poses): RMSE "
      << error.ate_rmse_m * 1e3 << " mm, max " << error.ate_max_m * 1e3 << " mm.";
  }
  return s.str();
}

void FuseSession::updateEsdf() {
  const EsdfUpdateStats stats = mapper_->updateEsdf();
  esdf_totals_.device_ms += stats.device_ms;
  esdf_totals_.wall_ms += stats.wall_ms;
  esdf_totals_.voxels_updated += stats.voxels_updated;
  esdf_totals_.blocks_updated += stats.blocks_updated;
}

bool FuseSession::run() {
  ProgressBar progress("fusing", frame_indices_.size(), !options_.quiet);
  const auto start = std::chrono::steady_clock::now();
  for (std::size_t i = 0; i < frame_indices_.size(); ++i) {
    bool fused = false;
    try {
      fused = fuseFrame(dataset_->load(frame_indices_[i]));
    } catch (const Error& e) {
      // NOTE: Mapper and the readers refuse a bad frame before the map changes, so skipping one
      // leaves the map as if it were not in the dataset; a device error is not the frame's.
      const bool bad_input = dynamic_cast<const InputError*>(&e) != nullptr;
      if (bad_input && options_.skip_bad_frames) {
        if (skipped_++ == 0) first_skipped_ = e.what();
        if (!options_.quiet || skipped_ <= 3) {
          std::fprintf(stderr, "\nstrata fuse: skipped frame %zu of %zu: %s\n", i + 1,
                       frame_indices_.size(), e.what());
        }
        continue;
      }
      progress.finish();
      failure_ = e.what();
      std::fprintf(stderr, "strata fuse: stopped at frame %zu of %zu: %s\n", i + 1,
                   frame_indices_.size(), e.what());
      std::fprintf(stderr, "strata fuse: no output written (%s)%s\n",
                   options_.map_path.empty() ? "no --map asked for"
                                             : previousMapNote().c_str(),
                   bad_input ? "; --skip-bad-frames fuses around frames like this one" : "");
      return false;
    }
    if (fused) ++fused_;
    std::ostringstream detail;
    if (mapper_ && fused_ > 0) {
      detail.precision(1);
      detail << std::fixed
             << (totals_.normals_ms + totals_.allocate_ms + totals_.integrate_ms) / fused_
             << " ms/frame on device";
      if (options_.esdf) detail << " + ESDF " << esdf_totals_.device_ms / fused_ << " ms";
      if (options_.track) detail << ", " << lost_ << " lost";
    }
    progress.update(i + 1, detail.str());
  }
  progress.finish();
  wall_s_ = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (skipped_ > 0 && skipped_ == frame_indices_.size()) {
    failure_ = "every frame was skipped (the first: " + first_skipped_ + ")";
    std::fprintf(stderr, "strata fuse: %s; no output written\n", failure_.c_str());
  }
  return failure_.empty();
}

bool FuseSession::writeOutputs() {
  if (mapper_) map_ = mapper_->download();
  // The map first: it is what a failure of any later output must not cost.
  const bool map_saved = options_.map_path.empty() || saveMapFile();
  if (!options_.mesh_path.empty() || analytic_ != nullptr) mesh_ = extractMesh(map_);
  if (!options_.mesh_path.empty()) {
    writePly(options_.mesh_path, mesh_);
    written_.push_back("mesh " + options_.mesh_path);
  }
  if (!options_.render_path.empty() && fused_ > 0) renderView();
  const bool slice_written = options_.esdf_png_path.empty() || writeEsdfSlice();
  const bool trajectory_written = options_.trajectory_path.empty() || writeTrajectory();
  return map_saved && slice_written && trajectory_written;
}

bool FuseSession::saveMapFile() {
  try {
    saveMap(map_, options_.map_path);  // the host copy just downloaded (Mapper::save would again)
  } catch (const Error& e) {
    // NOTE: the file is written atomically, so whatever was at the path before is still there:
    // say so, since that earlier map is all that is left once this process ends.
    std::fprintf(stderr, "strata fuse: the map was not saved: %s\n", e.what());
    std::fprintf(stderr, "strata fuse: %s\n", previousMapNote().c_str());
    map_save_problem_ = e.what();
    return false;
  }
  written_.push_back("map " + options_.map_path);
  return true;
}

std::string FuseSession::previousMapNote() const {
  std::error_code error;
  if (!std::filesystem::exists(options_.map_path, error)) {
    return "no map file is at '" + options_.map_path + "'";
  }
  return "'" + options_.map_path + "' still holds the map saved there before, unchanged";
}

bool FuseSession::writeEsdfSlice() {
  EsdfSliceOptions slice;
  slice.z_m = options_.slice_z_m;
  slice.max_distance_m = mapper_->config().esdf_config.max_distance_m;
  try {
    writeEsdfSlicePng(options_.esdf_png_path, mapper_->esdf(), slice);
  } catch (const InputError& e) {
    // NOTE: the fused map is worth more than the picture: keep going, report, exit non-zero.
    std::fprintf(stderr, "strata fuse: no ESDF slice written: %s\n", e.what());
    esdf_slice_problem_ = e.what();
    return false;
  }
  written_.push_back("ESDF slice " + options_.esdf_png_path);
  return true;
}

std::string FuseSession::esdfSummary() const {
  if (!options_.esdf || !mapper_ || fused_ == 0) return "";
  const double n = static_cast<double>(fused_);
  std::ostringstream s;
  s.precision(2);
  s << std::fixed << " ESDF kept up to date incrementally: " << esdf_totals_.device_ms / n
    << " ms per frame device time (" << esdf_totals_.wall_ms / n << " ms wall), "
    << std::llround(esdf_totals_.blocks_updated / n) << " blocks ("
    << std::llround(static_cast<double>(esdf_totals_.voxels_updated) / n)
    << " voxels) recomputed per frame.";
  if (!esdf_slice_problem_.empty()) s << " No ESDF slice: " << esdf_slice_problem_ << ".";
  return s.str();
}

void FuseSession::renderView() {
  RaycastImage image;
  if (mapper_) {
    image = mapper_->render(dataset_->intrinsics(), last_pose_);
  } else {
    image = raycastReference(map_, dataset_->intrinsics(), last_pose_);
  }
  writeColorPng(options_.render_path, shadedView(image, last_pose_));
  written_.push_back("rendering " + options_.render_path);
}

void FuseSession::printSummary() const {
  std::size_t observed = 0;
  for (const auto& [index, block] : map_.blocks()) {
    for (const TsdfVoxel& voxel : block) observed += voxel.weight > 0.0f ? 1 : 0;
  }
  std::ostringstream s;
  s.precision(2);
  s << std::fixed << "Fused " << fused_ << " of " << frame_indices_.size() << " frames of '"
    << dataset_->name() << "' (" << map_.config().describe() << ") into " << map_.blockCount()
    << " blocks, " << observed << " observed voxels, in " << wall_s_ << " s. ";
  if (mapper_ && fused_ > 0) {
    const double n = static_cast<double>(fused_);
    s << "Per frame on " << context_->deviceName() << ": upload " << totals_.upload_ms / n
      << " ms, normals " << totals_.normals_ms / n
      << " ms, allocate " << totals_.allocate_ms / n << " ms, integrate "
      << totals_.integrate_ms / n << " ms (device time), " << totals_.wall_ms / n
      << " ms wall; " << totals_.touched_blocks / fused_ << " blocks touched per frame. "
      << "Peak device memory " << context_->peakAllocatedBytes() / 1048576.0 << " MiB, ";
  } else if (fused_ > 0) {
    s << "C++ reference: " << reference_ms_ / static_cast<double>(fused_) << " ms per frame. ";
  }
  s << "peak host memory " << peakHostMemoryMiB() << " MiB." << esdfSummary()
    << trackingSummary();
  if (analytic_ != nullptr) {
    const float voxel_m = map_.config().voxel_size_m;
    const auto tsdf = eval::evaluateTsdf(map_, analytic_->scene(),
                                         0.5f * map_.config().truncationDistance());
    const auto mesh = eval::evaluateMesh(mesh_, analytic_->scene(), 0.5f * voxel_m);
    s << " Against the exact scene: mean |TSDF - SDF| " << tsdf.mean_abs_error_m / voxel_m
      << " voxel within half the band; " << mesh.fraction_within * 100.0
      << " % of " << mesh.vertices << " mesh vertices within half a voxel of the surface.";
  }
  for (const std::string& w : written_) s << " Wrote " << w << ".";
  if (skipped_ > 0) {
    s << " Skipped " << skipped_ << " bad frame" << (skipped_ == 1 ? "" : "s")
      << " (--skip-bad-frames; the first: " << first_skipped_ << ").";
  }
  if (!map_save_problem_.empty()) s << " Map not saved (" << previousMapNote() << ").";
  std::printf("%s\n", s.str().c_str());
}

}  // namespace strata::apps
