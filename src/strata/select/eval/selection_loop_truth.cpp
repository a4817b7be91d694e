#include "strata/select/eval/selection_loop_truth.h"

#include <stdexcept>

#include "strata/core/error.h"
#include "strata/map/camera_math.h"
#include "strata/raycast/tsdf_sampling.h"

namespace strata::selection {
namespace {

/// True surface points of a keyframe on a coarse grid (for mapCoverage).
void collectSurface(const sim::SimulatedFrame& frame, const Eigen::Isometry3d& true_T_W_C,
                    const CameraIntrinsics& k, std::vector<Eigen::Vector3f>& out) {
  constexpr int kStride = 8;
  const Eigen::Vector4f K(k.fx_px, k.fy_px, k.cx_px, k.cy_px);
  const Eigen::Isometry3f T_W_C = true_T_W_C.cast<float>();
  for (int v = kStride / 2; v < k.height_px; v += kStride) {
    for (int u = kStride / 2; u < k.width_px; u += kStride) {
      const std::size_t i = static_cast<std::size_t>(v) * k.width_px + u;
      if (!(frame.depth.depth_m[i] > 0.0f) || !(frame.depth_true.depth_m[i] > 0.0f)) continue;
      const Eigen::Vector3f ray_C = pixelRay(static_cast<float>(u), static_cast<float>(v), K);
      out.push_back(T_W_C * Eigen::Vector3f(ray_C * frame.depth_true.depth_m[i]));
    }
  }
}

}  // namespace

/// The simulated session as the loop loads it, keeping the latest rendering (with its truth
/// images) so that every frame is rendered once.
class LoopTruth::RenderedSession : public Dataset {
 public:
  explicit RenderedSession(const sim::SimSessionDataset& session) : session_(session) {}
  std::string name() const override { return session_.name(); }
  std::size_t size() const override { return session_.size(); }
  CameraIntrinsics intrinsics() const override { return session_.intrinsics(); }
  RgbdFrame load(std::size_t index) const override {
    last_ = session_.render(index);
    last_index_ = index;
    return sim::makeRgbdFrame(sim::SimulatedFrame(last_), session_.givenPoses()[index],
                              session_.timestamp(index),
                              session_.name() + " frame " + std::to_string(index));
  }
  /// The rendering of the frame loaded last; `index` must be that frame's.
  const sim::SimulatedFrame& rendered(std::size_t index) const {
    if (index != last_index_) throw std::logic_error("LoopTruth: frames seen out of order");
    return last_;
  }

 private:
  const sim::SimSessionDataset& session_;
  mutable sim::SimulatedFrame last_;
  mutable std::size_t last_index_ = static_cast<std::size_t>(-1);
};

LoopConfig demoLoopConfig(bool incremental) {
  LoopConfig c;
  c.map.voxel_size_m = 0.05f;
  c.map.weight_mode = WeightMode::kConstant;
  c.map.allocate_free_space = true;
  c.selection.smoothing_window = 1;
  c.selection.dilation = 0;
  c.incremental = incremental;
  c.with_reference = !incremental;
  c.changed_views.max_depth_m = c.map.max_depth_m;
  c.confirm.enabled = incremental;
  c.confirm.max_depth_m = c.map.max_depth_m;
  // Twice the gap-closing 0.75: an object standing as before is confirmed by few samples when
  // thin (a chair), so each vouches for the space up to the next-but-one sample (tuned on the
  // office; docs/select.md).
  c.confirm.radius_scale = 1.5f;
  c.keep_changed_views = incremental;
  return c;
}

LoopTruth::LoopTruth(const TruthConfig& config) : config_(config) { config_.validate(); }

const SessionRun& LoopTruth::addSession(SelectionLoop& loop, const sim::SimSessionDataset& session,
                                        const std::function<void(std::size_t)>& progress) {
  if (static_cast<std::size_t>(loop.sessions().size()) != truth_.size()) {
    throw InputError("LoopTruth: the loop ran sessions this recorder did not see");
  }
  const RenderedSession rendered(session);
  session_ = &session;
  rendered_ = &rendered;
  try {
    const SessionRun& run = loop.addSession(rendered, this, progress);
    session_ = nullptr, rendered_ = nullptr;
    return run;
  } catch (...) {
    session_ = nullptr, rendered_ = nullptr;
    throw;
  }
}

void LoopTruth::sessionStarted(int session, const TsdfMap& map_before) {
  truth_.emplace_back();
  session_surface_W_.clear();
  map_before_ = session > 0 ? std::make_unique<TsdfMap>(map_before) : nullptr;
}

void LoopTruth::frameLoaded(std::size_t index, const RgbdFrame& /*frame*/) {
  const sim::SimulatedFrame& frame = rendered_->rendered(index);
  const Eigen::Isometry3d& T_W_C = session_->truePoses()[index];
  session_surface_W_.emplace_back();
  collectSurface(frame, T_W_C, session_->intrinsics(), session_surface_W_.back());
  if (map_before_ == nullptr) return;
  const int s = static_cast<int>(truth_.size()) - 1;
  truth_.back().push_back(keyframeTruth(frame, T_W_C, session_->intrinsics(),
                                        session_->world().session(s).changedIds(), history_,
                                        *map_before_, config_));
}

void LoopTruth::sessionEnded(const SessionRun& run) {
  std::vector<Eigen::Vector3f> fused_surface_W;
  for (std::size_t i = 0; i < session_surface_W_.size(); ++i) {
    const std::vector<Eigen::Vector3f>& surface_W = session_surface_W_[i];
    seen_points_W_.insert(seen_points_W_.end(), surface_W.begin(), surface_W.end());
    if (run.fused.at(i)) {
      fused_surface_W.insert(fused_surface_W.end(), surface_W.begin(), surface_W.end());
    }
  }
  history_.addSession(session_->world().buildScene(run.session), fused_surface_W);
  session_surface_W_.clear();
  map_before_.reset();
}

const std::vector<KeyframeTruth>& LoopTruth::truth(int session) const {
  return truth_.at(static_cast<std::size_t>(session));
}

SurfaceCoverage LoopTruth::mapCoverage(SelectionLoop& loop) const {
  const TsdfMap map = loop.map();
  SurfaceCoverage c;
  const float voxel_m = map.config().voxel_size_m;
  for (const Eigen::Vector3f& p_W : seen_points_W_) {
    ++c.points;
    const GlobalVoxelIndex v = (p_W / voxel_m).array().floor().cast<int>();
    c.observed += observedVoxel(map, v, config_.min_weight) != nullptr;
  }
  return c;
}

}  // namespace strata::selection
