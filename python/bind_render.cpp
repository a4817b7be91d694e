// strata.Mapper's views of its map (bindings.h): render() (the device raycast of the live layer)
// and score_keyframe() (keyframe selection against the map), added to the Mapper class that
// bind_mapper.cpp made. The GIL is released during the device work.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <algorithm>
#include <sstream>
#include <string>

#include "bindings.h"
#include "convert.h"
#include "py_mapper.h"
#include "strata/core/error.h"
#include "strata/mapper/mapper.h"

namespace strata::python {
namespace {

/// A rendered view as arrays: depth H x W float32 (0 where the ray missed), colour H x W x 3
/// uint8, world normals H x W x 3 float32, hit H x W bool, and the device time.
struct PyRendering {
  py::array_t<float> depth;
  py::array_t<std::uint8_t> color;
  py::array_t<float> normals;
  py::array_t<bool> hit;
  double device_ms = 0.0;
};

PyRendering renderingFrom(const RaycastImage& image, const CameraIntrinsics& camera) {
  const py::ssize_t h = camera.height_px, w = camera.width_px;
  const auto pixels = static_cast<std::size_t>(h * w);
  PyRendering out;
  out.depth = py::array_t<float>({h, w});
  out.color = py::array_t<std::uint8_t>({h, w, py::ssize_t{3}});
  out.normals = py::array_t<float>({h, w, py::ssize_t{3}});
  out.hit = py::array_t<bool>({h, w});
  std::fill_n(out.depth.mutable_data(), pixels, 0.0f);
  std::fill_n(out.color.mutable_data(), 3 * pixels, std::uint8_t{0});
  std::fill_n(out.normals.mutable_data(), 3 * pixels, 0.0f);
  std::fill_n(out.hit.mutable_data(), pixels, false);
  if (image.depth.depth_m.size() == pixels) {
    std::copy(image.depth.depth_m.begin(), image.depth.depth_m.end(), out.depth.mutable_data());
  }
  if (image.color.rgb.size() == 3 * pixels) {
    std::copy(image.color.rgb.begin(), image.color.rgb.end(), out.color.mutable_data());
  }
  float* n = out.normals.mutable_data();
  for (std::size_t i = 0; i < std::min(pixels, image.normal_W.size()); ++i)
    for (int k = 0; k < 3; ++k) n[3 * i + k] = image.normal_W[i][k];
  bool* hit = out.hit.mutable_data();
  for (std::size_t i = 0; i < std::min(pixels, image.hit.size()); ++i) hit[i] = image.hit[i] != 0;
  return out;
}

}  // namespace

void bindRender(py::module_& m) {
  py::class_<PyRendering>(m, "Rendering",
                          "The live layer rendered into a camera (Mapper.render): depth, colour, "
                          "normals and hits as H x W arrays.")
      .def_readonly("depth", &PyRendering::depth,
                    "H x W float32: z in the camera frame, metres; 0 where the ray missed")
      .def_readonly("color", &PyRendering::color, "H x W x 3 uint8: the voxel colour at the hit")
      .def_readonly("normals", &PyRendering::normals,
                    "H x W x 3 float32: unit surface normal (world frame), 0 where missed")
      .def_readonly("hit", &PyRendering::hit, "H x W bool: the ray hit a surface")
      .def_readonly("device_ms", &PyRendering::device_ms, "Device time of the raycast")
      .def("__repr__", [](const PyRendering& r) {
        return "Rendering(" + std::to_string(r.depth.shape(1)) + " x " +
               std::to_string(r.depth.shape(0)) + ")";
      });

  using selection::KeyframeScore;
  py::class_<KeyframeDecision>(m, "KeyframeDecision",
                               "Mapper.score_keyframe: a frame's metrics against the map and "
                               "whether it is worth fusing (select/keyframe_scorer.h).")
      .def_readonly("keyframe", &KeyframeDecision::keyframe,
                    "Whether a metric passed its threshold")
      .def_readonly("reason", &KeyframeDecision::reason,
                    "The first metric over its threshold, or why none is")
      .def_readonly("device_ms", &KeyframeDecision::device_ms, "Device time of the scoring")
      .def_property_readonly(
          "samples", [](const KeyframeDecision& d) { return d.score.samples; },
          "Grid samples in the image")
      .def_property_readonly(
          "hits", [](const KeyframeDecision& d) { return d.score.hits; },
          "Samples (with measured depth) whose ray hits the map")
      .def_property_readonly(
          "coverage", [](const KeyframeDecision& d) { return d.score.coverage; },
          "hits / samples with measured depth, 0..1")
      .def_property_readonly(
          "color_change", [](const KeyframeDecision& d) { return d.score.color_change; },
          "Upper-half mean of the normalised colour differences (~0..1)")
      .def_property_readonly(
          "depth_change_m", [](const KeyframeDecision& d) { return d.score.depth_change_m; },
          "Upper-half mean of |measured - rendered depth| beyond the tolerance, metres")
      .def_property_readonly(
          "surface_change", [](const KeyframeDecision& d) { return d.score.surface_change; },
          "Share of measured samples whose point the map does not hold, 0..1")
      .def_property_readonly(
          "ncc", [](const KeyframeDecision& d) { return d.score.ncc; },
          "Baseline: normalised cross-correlation of the grey images, -1..1")
      .def_property_readonly(
          "histogram", [](const KeyframeDecision& d) { return d.score.histogram; },
          "Baseline: correlation of the grey-level histograms, -1..1")
      .def("__repr__", [](const KeyframeDecision& d) {
        std::ostringstream s;
        s << "KeyframeDecision(keyframe=" << (d.keyframe ? "True" : "False") << ", reason='"
          << d.reason << "', coverage=" << d.score.coverage
          << ", surface_change=" << d.score.surface_change << ")";
        return s.str();
      });

  auto mapper = py::reinterpret_borrow<py::class_<PyMapper>>(m.attr("Mapper"));
  mapper.def(
      "render",
      [](PyMapper& self, const py::array& T_W_C, const CameraIntrinsics& intrinsics) {
        const Eigen::Isometry3d pose = poseFrom(T_W_C, "T_W_C");
        intrinsics.validate();
        double device_ms = 0.0;
        const RaycastImage image =
            withoutGil(self, [&](Mapper& m) { return m.render(intrinsics, pose, &device_ms); });
        PyRendering out = renderingFrom(image, intrinsics);
        out.device_ms = device_ms;
        return out;
      },
      py::arg("T_W_C"), py::arg("intrinsics"),
      "Renders the live layer from T_W_C (4 x 4, camera to world) into the intrinsics' image "
      "(device raycast): a Rendering with depth H x W float32 (0 where nothing was hit), color "
      "H x W x 3 uint8, normals and hit.");
  mapper.def(
      "score_keyframe",
      [](PyMapper& self, const py::array& depth, const CameraIntrinsics& intrinsics,
         const py::array& T_W_C, const py::object& color, double depth_scale) {
        const Eigen::Isometry3d pose = poseFrom(T_W_C, "T_W_C");
        RgbdFrame& frame = frameFrom(self, depth, intrinsics, color, depth_scale);
        frame.T_W_C = pose;
        return withoutGil(self, [&](Mapper& m) { return m.scoreKeyframe(frame, intrinsics); });
      },
      py::arg("depth"), py::arg("intrinsics"), py::arg("T_W_C"), py::arg("color") = py::none(),
      py::arg("depth_scale") = 1000.0,
      "Scores a frame (the arrays of integrate) at T_W_C against the live layer as it is, "
      "without fusing it: a KeyframeDecision (coverage, colour, depth and surface change, the "
      "baselines, keyframe and reason). Needs MapperConfig(keyframe_scoring=True) "
      "(InputError otherwise).");
}

}  // namespace strata::python
