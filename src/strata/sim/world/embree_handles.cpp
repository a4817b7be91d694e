#include "strata/sim/world/internal/embree_handles.h"

#include <string>

#include "strata/core/error.h"

namespace strata::sim {
namespace {

const char* errorName(RTCError error) {
  switch (error) {
    case RTC_ERROR_NONE:
      return "RTC_ERROR_NONE";
    case RTC_ERROR_UNKNOWN:
      return "RTC_ERROR_UNKNOWN";
    case RTC_ERROR_INVALID_ARGUMENT:
      return "RTC_ERROR_INVALID_ARGUMENT";
    case RTC_ERROR_INVALID_OPERATION:
      return "RTC_ERROR_INVALID_OPERATION";
    case RTC_ERROR_OUT_OF_MEMORY:
      return "RTC_ERROR_OUT_OF_MEMORY";
    case RTC_ERROR_UNSUPPORTED_CPU:
      return "RTC_ERROR_UNSUPPORTED_CPU (Embree needs SSE2)";
    case RTC_ERROR_CANCELLED:
      return "RTC_ERROR_CANCELLED";
  }
  return "unknown RTCError";
}

}  // namespace

void checkEmbree(RTCDevice device, const char* call) {
  const RTCError error = rtcGetDeviceError(device);
  if (error != RTC_ERROR_NONE) {
    throw Error(std::string("Embree ") + call + " failed: " + errorName(error));
  }
}

RtcDevicePtr newEmbreeDevice() {
  RTCDevice device = rtcNewDevice(nullptr);
  if (device == nullptr) checkEmbree(nullptr, "rtcNewDevice");  // errors of a failed new device
  if (device == nullptr) throw Error("Embree rtcNewDevice failed");
  return RtcDevicePtr(device);
}

RtcScenePtr newEmbreeScene(RTCDevice device) {
  RtcScenePtr scene(rtcNewScene(device));
  checkEmbree(device, "rtcNewScene");
  rtcSetSceneFlags(scene.get(), RTC_SCENE_FLAG_ROBUST | RTC_SCENE_FLAG_CONTEXT_FILTER_FUNCTION);
  checkEmbree(device, "rtcSetSceneFlags");
  return scene;
}

}  // namespace strata::sim
