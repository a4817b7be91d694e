#pragma once
// The Python package's bindings, one function per part of the module (strata_module.cpp calls
// them in order: the configs before the Mapper that takes them).
#include <pybind11/pybind11.h>

namespace strata::python {

namespace py = pybind11;

void bindConfigs(py::module_& m);     // MapConfig, MapperConfig, CameraIntrinsics
void bindMapper(py::module_& m);      // Mesh, DiscoveredObject, Mapper
void bindRender(py::module_& m);      // Rendering, KeyframeDecision, Mapper.render/score_keyframe
void bindIo(py::module_& io);         // Dataset
void bindSim(py::module_& sim);       // session() -> Dataset
void bindTrajectory(py::module_& t);  // evaluate, TrajectoryError
void bindOdometry(py::module_& o);    // run_euroc, VioRun
void bindVio(py::module_& o);         // Vio, VioFrame (fed live)
void bindPlan(py::module_& p);        // plan, PlanResult
void bindStore(py::module_& s);       // Store, Session, ImportResult
void bindObjects(py::module_& o);     // build, ObjectDatabase, ObjectModel
void bindExplore(py::module_& e);     // run, ExplorationRun
void bindAlign(py::module_& a);       // align_store, Alignment, AlignedSession, AlignmentScore
void bindLocalize(py::module_& l);    // PriorMap, Localizer, PoseFusion, localize_session

}  // namespace strata::python
