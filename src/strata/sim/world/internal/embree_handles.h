#pragma once
// RAII for Embree handles, and Embree errors as strata::Error (internal to the world module).
#include <embree3/rtcore.h>

#include <utility>

namespace strata::sim {

/// Owns one reference to an Embree object; released on destruction. Move-only.
template <typename Handle, void (*Release)(Handle)>
class RtcHandle {
 public:
  RtcHandle() = default;
  explicit RtcHandle(Handle handle) : handle_(handle) {}
  RtcHandle(RtcHandle&& other) noexcept : handle_(std::exchange(other.handle_, nullptr)) {}
  RtcHandle& operator=(RtcHandle&& other) noexcept {
    if (this != &other) {
      reset();
      handle_ = std::exchange(other.handle_, nullptr);
    }
    return *this;
  }
  RtcHandle(const RtcHandle&) = delete;
  RtcHandle& operator=(const RtcHandle&) = delete;
  ~RtcHandle() { reset(); }

  Handle get() const { return handle_; }
  void reset() {
    if (handle_ != nullptr) Release(handle_);
    handle_ = nullptr;
  }

 private:
  Handle handle_ = nullptr;
};

using RtcDevicePtr = RtcHandle<RTCDevice, rtcReleaseDevice>;
using RtcScenePtr = RtcHandle<RTCScene, rtcReleaseScene>;
using RtcGeometryPtr = RtcHandle<RTCGeometry, rtcReleaseGeometry>;

/// Throws strata::Error "Embree <call> failed: <code>" when the device has an error pending.
void checkEmbree(RTCDevice device, const char* call);

/// A new device; Error naming rtcNewDevice and the code when Embree cannot start (e.g. no SSE2).
RtcDevicePtr newEmbreeDevice();

/// A new scene with the flags every world scene uses: robust traversal (no rays slipping between
/// triangles that share an edge) and context filter functions (used to count ray crossings).
RtcScenePtr newEmbreeScene(RTCDevice device);

}  // namespace strata::sim
