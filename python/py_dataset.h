#pragma once
// strata.io.Dataset's C++ side, shared by the parts of the module that read datasets
// (bind_data.cpp, bind_objects.cpp): a library Dataset whose frames come out as numpy arrays.
// Thread safety: as the Dataset (its load() is const).
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <algorithm>
#include <memory>
#include <string>

#include "convert.h"
#include "strata/core/dataset.h"
#include "strata/io/open_dataset.h"
#include "strata/sim/session/sim_session.h"

namespace strata::python {

namespace py = pybind11;

/// A dataset folder (TUM RGB-D, 7-Scenes) as a sequence of frames.
class PyDataset {
 public:
  explicit PyDataset(const std::string& path) : dataset_(openDataset(path)) {}
  explicit PyDataset(std::unique_ptr<Dataset> dataset) : dataset_(std::move(dataset)) {}
  std::size_t size() const { return dataset_->size(); }
  CameraIntrinsics intrinsics() const { return dataset_->intrinsics(); }
  std::string name() const { return dataset_->name(); }
  /// The library's dataset (for calls that read its frames themselves).
  const Dataset& dataset() const { return *dataset_; }
  /// Frames of the whole recording the dataset's frames were drawn from (a simulated session's
  /// path at its rate); size() for other datasets.
  std::size_t recordedFrames() const {
    const auto* sim = dynamic_cast<const sim::SimSessionDataset*>(dataset_.get());
    return sim ? sim->recordedFrames() : size();
  }
  py::dict frame(std::ptrdiff_t index) const {
    const auto n = static_cast<std::ptrdiff_t>(size());
    if (index < 0) index += n;
    if (index < 0 || index >= n) throw py::index_error("frame index out of range");
    RgbdFrame f;
    {
      py::gil_scoped_release release;
      f = dataset_->load(static_cast<std::size_t>(index));
    }
    py::array_t<float> depth({f.depth.height_px, f.depth.width_px});
    std::copy(f.depth.depth_m.begin(), f.depth.depth_m.end(), depth.mutable_data());
    py::dict out;
    out["depth"] = depth;
    if (!f.color.empty()) {
      py::array_t<std::uint8_t> color({f.color.height_px, f.color.width_px, 3});
      std::copy(f.color.rgb.begin(), f.color.rgb.end(), color.mutable_data());
      out["color"] = color;
    } else {
      out["color"] = py::none();
    }
    out["T_W_C"] = poseTo(f.T_W_C);
    out["timestamp_s"] = f.timestamp_s;
    out["name"] = f.name;
    return out;
  }

 private:
  std::unique_ptr<Dataset> dataset_;
};

}  // namespace strata::python
