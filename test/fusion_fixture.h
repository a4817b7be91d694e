#pragma once
// Shared pieces of the fusion tests: one Vulkan context per test program, device and reference
// fusion of a dataset's frames.
#include <gtest/gtest.h>

#include <memory>

#include "strata/io/open_dataset.h"
#include "strata/integrate/device_fusion.h"
#include "strata/map/tsdf_map.h"
#include "strata/vk/vk.h"

namespace strata::test {

/// Lazily created, validation on (the test environment sets STRATA_VALIDATION=1).
vk::Context& sharedContext();

/// Fuses frames [0, count) with step `stride` on the device; returns the downloaded map.
TsdfMap fuseOnDevice(const Dataset& dataset, const MapConfig& config, std::size_t count,
                     std::size_t stride = 1, DeviceFusion* fusion = nullptr);

/// The same frames with the C++ reference.
TsdfMap fuseReference(const Dataset& dataset, const MapConfig& config, std::size_t count,
                      std::size_t stride = 1);

}  // namespace strata::test
