// The compiled part of the Python package `strata` (strata._strata): the C++ types and calls
// as they are, with numpy arrays in and out (convert.h; conventions in docs/python.md). Errors:
// C++ InputError -> strata.InputError (a ValueError), DeviceError -> strata.DeviceError, other
// strata::Error -> strata.Error. The GIL is released during device work and long host work, so
// other Python threads run meanwhile; one Mapper must not be used by two threads at once.
#include <pybind11/pybind11.h>

#include "bindings.h"
#include "convert.h"
#include "strata/core/error.h"
#include "strata/vk/vk.h"

namespace py = pybind11;

PYBIND11_MODULE(_strata, m) {
  using namespace strata;
  using namespace strata::python;
  m.doc() = "Strata: dense multi-session mapping (the C++ library's types and calls)";
  static py::exception<Error> error(m, "Error", PyExc_RuntimeError);
  static py::exception<InputError> input_error(m, "InputError", PyExc_ValueError);
  static py::exception<DeviceError> device_error(m, "DeviceError", error.ptr());
  error.attr("__doc__") = "An error of the library (a RuntimeError), with its message.";
  input_error.attr("__doc__") =
      "Bad input (a ValueError): a wrong dtype, shape, value or file, refused before any work.";
  device_error.attr("__doc__") = "The device failed or is full (a strata.Error).";
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const InputError& e) {
      input_error(e.what());
    } catch (const DeviceError& e) {
      device_error(e.what());
    } catch (const Error& e) {
      error(e.what());
    }
  });
  bindConfigs(m);
  bindMapper(m);
  bindRender(m);
  py::module_ io = m.def_submodule("io", "Datasets as arrays");
  bindIo(io);
  py::module_ trajectory = m.def_submodule("trajectory", "Trajectory accuracy (ATE, RPE)");
  bindTrajectory(trajectory);
  py::module_ sim = m.def_submodule("sim", "The simulator's worlds and sessions");
  bindSim(sim);
  py::module_ odometry = m.def_submodule("odometry", "Visual-inertial odometry");
  bindOdometry(odometry);
  bindVio(odometry);
  py::module_ plan = m.def_submodule("plan", "Path planning on a Mapper's ESDF");
  bindPlan(plan);
  py::module_ store = m.def_submodule("store", "The session store: many sessions in one map");
  bindStore(store);
  py::module_ align = m.def_submodule("align", "Multi-session alignment of a store's sessions");
  bindAlign(align);
  py::module_ localize = m.def_submodule("localize", "Localisation against a prior map store");
  bindLocalize(localize);
  py::module_ objects = m.def_submodule("objects", "The object database over sessions");
  bindObjects(objects);
  py::module_ explore = m.def_submodule("explore", "Closed-loop exploration of simulated worlds");
  bindExplore(explore);
  m.def("input_copies", &inputCopies,
        "Input arrays (depth, colour, points) the bindings converted into a temporary so far in "
        "this process: another dtype or not C-contiguous. Arrays in the library's dtype and C "
        "order are read in place and leave it unchanged.");
  m.def("validation_errors", &vk::validationErrorCount,
        "Vulkan validation errors reported so far in this process (STRATA_VALIDATION=1 turns the "
        "layer on); tests assert 0.");
}
