// ChangeDetector on the device: S is TSDF layer 0 (what raycasts and the ESDF read by default);
// label layers: D = 0, the passes' raw labels 1. Each session has a TSDF and a label layer (P_i)
// of its own: appended, or those of a released session, cleared.
#include "strata/change/internal/change_backend.h"
#include "strata/change/change_detector.h"
#include "strata/change/change_device.h"

#include <vector>

namespace strata::change {
namespace {

constexpr int kStaticLayer = 0;
constexpr int kLabelLayer = 0;
constexpr int kRawScratch = 1;

class DeviceBackend final : public ChangeBackend {
 public:
  DeviceBackend(vk::Context& context, const MapConfig& map_config, const ChangeConfig& config)
      : fusion_(context, map_config), change_(context, fusion_.map(), config) {
    for (int layer = 0; layer <= kRawScratch; ++layer) fusion_.map().addLabelLayer();
  }

  void addSession(int) override {
    SessionLayers layers;
    if (released_.empty()) {
      layers = {fusion_.map().addTsdfLayer(), fusion_.map().addLabelLayer()};
    } else {
      layers = released_.back();
      released_.pop_back();
      fusion_.map().clearTsdfLayer(layers.tsdf);
      fusion_.map().clearLabelLayer(layers.labels);
    }
    session_layers_.push_back(layers);
  }

  void releaseSession(int session) override {
    released_.push_back(session_layers_[session]);
    session_layers_[session] = SessionLayers{};
  }

  void restore(const TsdfMap& static_map, int ended_sessions) override {
    fusion_.map().uploadLayer(static_map, kStaticLayer);
    session_layers_.assign(static_cast<std::size_t>(ended_sessions), SessionLayers{});
  }

  int sessionTsdfLayer(int session) const override { return session_layers_[session].tsdf; }

  FrameStats integrate(int session, const RgbdFrame& frame,
                       const CameraIntrinsics& intrinsics) override {
    return fusion_.integrate(frame, intrinsics, sessionTsdfLayer(session));
  }

  void setSessionMap(int session, const TsdfMap& map) override {
    fusion_.map().uploadLayer(map, sessionTsdfLayer(session));
  }

  ChangeUpdateStats update(int session) override { return change_.update(layers(session)); }
  void refreshDynamic(int session) override { change_.dynamicParts(layers(session)); }

  TsdfMap staticMap() override { return download(kStaticLayer); }
  TsdfMap sessionMap(int session) override { return download(sessionTsdfLayer(session)); }
  LabelMap labels() override { return downloadLabels(fusion_.map(), kLabelLayer); }
  LabelMap sessionDynamic(int session) override {
    return downloadLabels(fusion_.map(), session_layers_[session].labels);
  }
  DeviceTsdfMap* deviceMap() override { return &fusion_.map(); }
  DeviceFusion* deviceFusion() override { return &fusion_; }

 private:
  struct SessionLayers {
    int tsdf = -1;
    int labels = -1;  // the session's dynamic part P_i
  };

  /// Session `session` merged into S, and its dynamic part.
  ChangeLayers layers(int session) const {
    const SessionLayers& own = session_layers_[session];
    ChangeLayers layers;
    layers.static_tsdf = kStaticLayer;
    layers.session_tsdf = own.tsdf;
    layers.labels = kLabelLayer;
    layers.raw_scratch = kRawScratch;
    layers.session_parts = {{own.tsdf, own.labels}};
    return layers;
  }

  TsdfMap download(int layer) {
    TsdfMap map(fusion_.config());
    fusion_.map().download(map, layer);
    return map;
  }

  DeviceFusion fusion_;
  DeviceChange change_;
  std::vector<SessionLayers> session_layers_;  // by session; released ones -1
  std::vector<SessionLayers> released_;        // free for the next session
};

}  // namespace

std::unique_ptr<ChangeBackend> makeDeviceBackend(vk::Context& context, const MapConfig& map_config,
                                                 const ChangeConfig& config) {
  return std::make_unique<DeviceBackend>(context, map_config, config);
}

}  // namespace strata::change
