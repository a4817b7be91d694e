#pragma once
// strata.Mapper's C++ side, shared by the parts of the module that take a Mapper (bind_mapper.cpp,
// bind_plan.cpp): a strata::Mapper with the device context it needs, a frame buffer the numpy
// arrays are copied into (reused, so a call allocates nothing once the image size is known), and
// the duration of its last library call, measured in C++ around the call alone.
// Thread safety: one PyMapper must not be used by two threads at once (as strata::Mapper).
#include <pybind11/pybind11.h>

#include <chrono>
#include <memory>
#include <string>

#include "convert.h"
#include "strata/core/error.h"
#include "strata/mapper/mapper.h"
#include "strata/vk/vk.h"

namespace strata::python {

namespace py = pybind11;

class PyMapper {
 public:
  PyMapper(const MapperConfig& config, const std::string& device) : context_(makeContext(device)) {
    mapper_ = std::make_unique<Mapper>(config, *context_);
  }
  PyMapper(std::unique_ptr<vk::Context> context, std::unique_ptr<Mapper> mapper)
      : context_(std::move(context)), mapper_(std::move(mapper)) {}

  /// device: "" (automatic), an index or a name substring.
  static std::unique_ptr<vk::Context> makeContext(const std::string& device) {
    vk::ContextOptions options;
    options.device_selector = device;
    options.log_device = false;
    return vk::Context::create(options);
  }

  /// InputError once closed.
  Mapper& mapper() {
    if (!mapper_) throw InputError("the mapper is closed");
    return *mapper_;
  }
  void close() {
    mapper_.reset();
    context_.reset();
    frame_ = RgbdFrame{};
  }
  /// The frame integrate() and track_and_integrate() fill from the arrays (its buffers are kept).
  RgbdFrame& frameBuffer() { return frame_; }
  /// Seconds of the last call made through withoutGil (0 before any).
  double lastCallSeconds() const { return last_call_s_; }
  void setLastCallSeconds(double s) { last_call_s_ = s; }

 private:
  std::unique_ptr<vk::Context> context_;
  std::unique_ptr<Mapper> mapper_;
  RgbdFrame frame_;
  double last_call_s_ = 0.0;
};

/// `work(mapper)` with the GIL released (other Python threads run meanwhile); its result is
/// returned once the GIL is held again. Its duration (work alone, no conversion) is kept as the
/// mapper's last call time.
template <typename Work>
auto withoutGil(PyMapper& self, Work work) {
  Mapper& mapper = self.mapper();
  py::gil_scoped_release release;
  const auto start = std::chrono::steady_clock::now();
  auto result = work(mapper);
  self.setLastCallSeconds(
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
  return result;
}

/// The mapper's frame buffer filled from the arrays (convert.h) and validated against the
/// intrinsics: what integrate(), track_and_integrate() and score_keyframe() read.
inline RgbdFrame& frameFrom(PyMapper& self, const py::array& depth,
                            const CameraIntrinsics& intrinsics, const py::object& color,
                            double depth_scale) {
  RgbdFrame& frame = self.frameBuffer();
  depthInto(depth, depth_scale, frame.depth);
  colorInto(color, frame.color);
  validateFrame(frame, intrinsics);
  return frame;
}

}  // namespace strata::python
