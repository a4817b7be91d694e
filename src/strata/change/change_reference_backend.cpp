// ChangeDetector in reference mode: host maps, C++ reference fusion (integrateFrameReference) and
// passes (change_reference.h), each stage timed with the host clock.
#include <chrono>

#include "strata/change/internal/change_backend.h"
#include "strata/change/change_reference.h"
#include "strata/core/clock.h"
#include "strata/integrate/tsdf_integration.h"

namespace strata::change {
namespace {

using Clock = std::chrono::steady_clock;

class ReferenceBackend final : public ChangeBackend {
 public:
  ReferenceBackend(const MapConfig& map_config, const ChangeConfig& config)
      : map_config_(map_config), config_(config), static_(map_config) {
    labels_.voxel_size_m = map_config.voxel_size_m;
  }

  void addSession(int) override {
    sessions_.emplace_back(map_config_);
    parts_.emplace_back();
    parts_.back().voxel_size_m = map_config_.voxel_size_m;
  }

  FrameStats integrate(int session, const RgbdFrame& frame,
                       const CameraIntrinsics& intrinsics) override {
    const auto start = Clock::now();
    FrameStats stats;
    stats.touched_blocks = static_cast<std::uint32_t>(
        integrateFrameReference(sessions_[session], frame, intrinsics).size());
    stats.wall_ms = msSince(start);
    stats.integrate_ms = stats.wall_ms;
    return stats;
  }

  void releaseSession(int session) override {
    sessions_[session] = TsdfMap(map_config_);
    parts_[session] = LabelMap{};
  }

  void setSessionMap(int session, const TsdfMap& map) override { sessions_[session] = map; }

  void restore(const TsdfMap& static_map, int ended_sessions) override {
    static_ = static_map;
    sessions_.assign(static_cast<std::size_t>(ended_sessions), TsdfMap(map_config_));
    parts_.assign(static_cast<std::size_t>(ended_sessions), LabelMap{});
  }

  ChangeUpdateStats update(int session) override {
    const auto wall_start = Clock::now();
    ChangeUpdateStats stats;
    const TsdfMap& m = sessions_[session];
    auto stage = [](double& ms, auto&& fn) {
      const auto start = Clock::now();
      fn();
      ms = msSince(start);
    };
    LabelMap raw, eroded;
    ChangeStageTimes& t = stats.stages;
    stage(t.difference_ms, [&] { raw = differenceReference(static_, m, config_); });
    stage(t.erosion_ms, [&] { eroded = erodeReference(raw, config_.erosion_kernel_voxels); });
    stage(t.dilation_ms, [&] {
      labels_ =
          dilateReference(raw, eroded, config_.dilation_kernel_voxels, DilationMask::kObserved);
    });
    stage(t.static_update_ms, [&] { staticUpdateReference(static_, m, labels_, config_); });
    stage(t.session_dynamic_ms, [&] { refreshDynamic(session); });
    stats.blocks = static_cast<std::uint32_t>(static_.blockCount());
    stats.voxels = std::uint64_t{stats.blocks} * kVoxelsPerBlock;
    stats.raw_dynamic_voxels = raw.count(VoxelLabel::kDynamic);
    stats.eroded_dynamic_voxels = eroded.count(VoxelLabel::kDynamic);
    stats.dynamic_voxels = labels_.count(VoxelLabel::kDynamic);
    stats.session_dynamic_voxels = parts_[session].count(VoxelLabel::kDynamic);
    stats.wall_ms = msSince(wall_start);
    return stats;
  }

  void refreshDynamic(int session) override {
    parts_[session] =
        cleanLabelsReference(sessionDynamicRawReference(sessions_[session], static_, config_),
                             config_, DilationMask::kRawDynamic);
  }

  TsdfMap staticMap() override { return static_; }
  TsdfMap sessionMap(int session) override { return sessions_[session]; }
  LabelMap labels() override { return labels_; }
  LabelMap sessionDynamic(int session) override { return parts_[session]; }

 private:
  MapConfig map_config_;
  ChangeConfig config_;
  TsdfMap static_;
  LabelMap labels_;
  std::vector<TsdfMap> sessions_;
  std::vector<LabelMap> parts_;
};

}  // namespace

std::unique_ptr<ChangeBackend> makeReferenceBackend(const MapConfig& map_config,
                                                    const ChangeConfig& config) {
  return std::make_unique<ReferenceBackend>(map_config, config);
}

}  // namespace strata::change
