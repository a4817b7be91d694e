// strata.odometry.Vio (bindings.h): visual-inertial odometry fed live, one IMU sample or camera
// frame at a time, as strata-vio feeds it (odometry/pipeline/vio_pipeline.h): each push returns
// the frames it completed, with their pose and status. The GIL is released while a frame is
// processed.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <memory>
#include <string>
#include <vector>

#include "bindings.h"
#include "convert.h"
#include "strata/core/error.h"
#include "strata/io/euroc_dataset.h"
#include "strata/odometry/pipeline/vio_pipeline.h"

namespace strata::python {
namespace {

/// A grey uint8 H x W array as a GreyImage (copied); None gives an empty image.
GreyImage greyFrom(const py::object& image, const char* eye) {
  GreyImage out;
  if (image.is_none()) return out;
  const py::array a = py::array::ensure(image);
  if (!a || a.ndim() != 2 || !py::isinstance<py::array_t<std::uint8_t>>(a)) {
    throw InputError(std::string(eye) + " must be a uint8 H x W (grey) array, not " +
                     (a ? describe(a) : std::string("a non-array")));
  }
  const auto c = py::array_t<std::uint8_t, py::array::c_style | py::array::forcecast>::ensure(a);
  out.height_px = static_cast<int>(a.shape(0));
  out.width_px = static_cast<int>(a.shape(1));
  out.pixels.assign(c.data(), c.data() + a.size());
  return out;
}

Eigen::Vector3d vectorFrom(const py::object& v, const char* what) {
  const auto a = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(v);
  if (!a || a.size() != 3) {
    PyErr_Clear();
    throw InputError(std::string(what) + " must be 3 numbers, not " + std::string(py::repr(v)));
  }
  return {a.data()[0], a.data()[1], a.data()[2]};
}

/// A VioPipeline made from an EuRoC folder's calibration.
class PyVio {
 public:
  PyVio(const std::string& folder, bool mono, int window) {
    euroc::ReaderOptions reader;
    reader.use_right_camera = !mono;
    const euroc::EurocDataset dataset = euroc::EurocDataset::open(folder, reader);
    odometry::VioPipelineConfig config;
    config.mono = mono || !dataset.stereo();
    config.backend.window_size = window;
    config.validate();
    pipeline_ = std::make_unique<odometry::VioPipeline>(dataset.calibration(), config);
  }
  std::vector<odometry::PipelineFrame> pushImu(std::int64_t t_ns, const py::object& gyro,
                                               const py::object& accel) {
    euroc::ImuSample s;
    s.timestamp_ns = t_ns;
    s.gyro_rad_s = vectorFrom(gyro, "gyro_rad_s");
    s.accel_mps2 = vectorFrom(accel, "accel_mps2");
    py::gil_scoped_release release;
    return pipeline_->pushImu(s);
  }
  std::vector<odometry::PipelineFrame> pushFrame(std::int64_t t_ns, const py::object& left,
                                                 const py::object& right) {
    if (left.is_none()) throw InputError("left must be a uint8 H x W (grey) array, not None");
    const GreyImage l = greyFrom(left, "left"), r = greyFrom(right, "right");
    py::gil_scoped_release release;
    return pipeline_->pushFrame(t_ns, l, r);
  }
  odometry::VioPipeline& pipeline() { return *pipeline_; }

 private:
  std::unique_ptr<odometry::VioPipeline> pipeline_;
};

py::dict statsOf(const odometry::PipelineStats& s) {
  py::dict d;
  d["imu_samples"] = s.imu_samples;
  d["imu_nonfinite_skipped"] = s.imu_nonfinite_skipped;
  d["imu_out_of_range_skipped"] = s.imu_out_of_range_skipped;
  d["imu_out_of_order_skipped"] = s.imu_out_of_order_skipped;
  d["frames_in"] = s.frames_in;
  d["frames_processed"] = s.frames_processed;
  d["frames_out_of_order_skipped"] = s.frames_out_of_order_skipped;
  d["frames_without_imu_skipped"] = s.frames_without_imu_skipped;
  d["frames_tracking"] = s.frames_tracking;
  d["frames_initializing"] = s.frames_initializing;
  d["failures"] = s.failures;
  return d;
}

}  // namespace

void bindVio(py::module_& o) {
  using odometry::PipelineFrame;
  py::class_<PipelineFrame>(o, "VioFrame", "One processed frame of Vio (PipelineFrame).")
      .def_readonly("timestamp_ns", &PipelineFrame::timestamp_ns)
      .def_property_readonly(
          "status", [](const PipelineFrame& f) { return std::string(toString(f.status)); },
          "'initializing', 'tracking' or 'failed'")
      .def_readonly("reason", &PipelineFrame::reason,
                    "Why it failed, or what initialisation waits for")
      .def_property_readonly(
          "T_W_C", [](const PipelineFrame& f) { return poseTo(f.T_W_C); },
          "4 x 4 left camera to world (tracking only)")
      .def_property_readonly(
          "T_W_B", [](const PipelineFrame& f) { return poseTo(f.T_W_B); },
          "4 x 4 body (IMU) to world (tracking only)")
      .def_property_readonly(
          "v_W_B", [](const PipelineFrame& f) { return Eigen::Vector3d(f.v_W_B); },
          "3: body velocity in the world, m/s")
      .def_readonly("segment", &PipelineFrame::segment, "+1 at each re-initialisation")
      .def_readonly("features", &PipelineFrame::features)
      .def_readonly("landmarks", &PipelineFrame::landmarks)
      .def("__repr__", [](const PipelineFrame& f) {
        return "VioFrame(" + std::to_string(f.timestamp_ns) + ", " + toString(f.status) + ")";
      });

  py::class_<PyVio>(o, "Vio",
                    "Visual-inertial odometry fed live: push IMU samples and camera frames in "
                    "time order, one at a time; each push returns the frames it completed "
                    "(a frame waits for an IMU sample at or after its time).")
      .def(py::init<const std::string&, bool, int>(), py::arg("calibration_folder"),
           py::arg("mono") = false, py::arg("window") = 10,
           "The cameras and IMU of an EuRoC/ASL folder (mav0/*/sensor.yaml); mono: the left "
           "camera only.")
      .def("push_imu", &PyVio::pushImu, py::arg("timestamp_ns"), py::arg("gyro_rad_s"),
           py::arg("accel_mps2"),
           "One IMU sample (body frame, EuRoC's clock): [VioFrame] it completed. Non-finite or "
           "out-of-order samples are counted and skipped.")
      .def("push_frame", &PyVio::pushFrame, py::arg("timestamp_ns"), py::arg("left"),
           py::arg("right") = py::none(),
           "One camera frame: grey uint8 H x W images of the calibrated size (right None for "
           "mono): [VioFrame] processed now. A wrong image raises InputError naming the eye, "
           "with nothing changed.")
      .def(
          "flush", [](PyVio& self) { self.pipeline().flush(); },
          "End of stream: frames still waiting for IMU are dropped (counted).")
      .def_property_readonly(
          "stereo", [](PyVio& self) { return self.pipeline().stereo(); }, "Two cameras")
      .def_property_readonly(
          "status", [](PyVio& self) { return std::string(toString(self.pipeline().status())); },
          "'initializing', 'tracking' or 'failed'")
      .def_property_readonly(
          "stats", [](PyVio& self) { return statsOf(self.pipeline().stats()); },
          "dict of counts: imu_samples, *_skipped, frames_in, frames_processed, "
          "frames_tracking, frames_initializing, failures");
}

}  // namespace strata::python
