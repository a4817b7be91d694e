#include "fusion_fixture.h"

#include "strata/integrate/tsdf_integration.h"

namespace strata::test {

vk::Context& sharedContext() {
  static std::unique_ptr<vk::Context> context = [] {
    vk::ContextOptions options;
    options.log_device = false;
    return vk::Context::create(options);
  }();
  return *context;
}

TsdfMap fuseOnDevice(const Dataset& dataset, const MapConfig& config, std::size_t count,
                     std::size_t stride, DeviceFusion* fusion) {
  std::unique_ptr<DeviceFusion> owned;
  if (fusion == nullptr) {
    owned = std::make_unique<DeviceFusion>(sharedContext(), config);
    fusion = owned.get();
  }
  for (std::size_t i = 0; i < count && i < dataset.size(); i += stride) {
    fusion->integrate(dataset.load(i), dataset.intrinsics());
  }
  TsdfMap map(config);
  fusion->map().download(map);
  return map;
}

TsdfMap fuseReference(const Dataset& dataset, const MapConfig& config, std::size_t count,
                      std::size_t stride) {
  TsdfMap map(config);
  for (std::size_t i = 0; i < count && i < dataset.size(); i += stride) {
    integrateFrameReference(map, dataset.load(i), dataset.intrinsics());
  }
  return map;
}

}  // namespace strata::test
