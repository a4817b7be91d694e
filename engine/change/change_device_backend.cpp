// ChangeDetector on the device: S is TSDF layer 0 (what raycasts and the ESDF read by default),
// session i is TSDF layer i + 1; label layers: D = 0, the passes' raw labels 1, P_i = 2 + i.
#include "change/internal/change_backend.h"
#include "change/change_detector.h"
#include "change/change_device.h"

namespace strata::change {
namespace {

constexpr int kStaticLayer = 0;
constexpr int kLabelLayer = 0;
constexpr int kRawScratch = 1;

int sessionTsdfLayer(int session) { return ChangeDetector::sessionLayer(session); }
int sessionLabelLayer(int session) { return session + 2; }

class DeviceBackend final : public ChangeBackend {
 public:
  DeviceBackend(vk::Context& context, const MapConfig& map_config, const ChangeConfig& config)
      : fusion_(context, map_config), change_(context, fusion_.map(), config) {
    for (int layer = 0; layer <= kRawScratch; ++layer) fusion_.map().addLabelLayer();
  }

  void addSession(int) override {
    // Layers are only ever appended, one TSDF and one label layer per session, in order.
    fusion_.map().addTsdfLayer();
    fusion_.map().addLabelLayer();
  }

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
    return downloadLabels(fusion_.map(), sessionLabelLayer(session));
  }
  DeviceTsdfMap* deviceMap() override { return &fusion_.map(); }
  DeviceFusion* deviceFusion() override { return &fusion_; }

 private:
  /// Session `session` merged into S, and its dynamic part.
  static ChangeLayers layers(int session) {
    ChangeLayers layers;
    layers.static_tsdf = kStaticLayer;
    layers.session_tsdf = sessionTsdfLayer(session);
    layers.labels = kLabelLayer;
    layers.raw_scratch = kRawScratch;
    layers.session_parts = {{sessionTsdfLayer(session), sessionLabelLayer(session)}};
    return layers;
  }

  TsdfMap download(int layer) {
    TsdfMap map(fusion_.config());
    fusion_.map().download(map, layer);
    return map;
  }

  DeviceFusion fusion_;
  DeviceChange change_;
};

}  // namespace

std::unique_ptr<ChangeBackend> makeDeviceBackend(vk::Context& context, const MapConfig& map_config,
                                                 const ChangeConfig& config) {
  return std::make_unique<DeviceBackend>(context, map_config, config);
}

}  // namespace strata::change
