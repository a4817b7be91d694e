// strata.objects (bindings.h): the object database over sessions, as `strata objects` builds it:
// the sessions fused one after the other with change detection (DiffPipeline), every session's
// moved objects discovered against the final static map, then added to the incremental object
// database (objects/object_database.h), which matches them into models. The GIL is released
// while it runs.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <chrono>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "bindings.h"
#include "convert.h"
#include "py_dataset.h"
#include "py_mapper.h"
#include "strata/change/change_config.h"
#include "strata/core/error.h"
#include "strata/core/progress.h"
#include "strata/mapper/session_diff.h"
#include "strata/objects/object_database.h"

namespace strata::python {
namespace {

/// What build() made: the database, each segment's outcome, the sessions' discoveries.
struct PyObjectDatabase {
  objects::ObjectDatabase database;
  std::vector<objects::SegmentOutcome> outcomes;                  // every session's, in order
  std::vector<std::vector<change::DiscoveredObject>> discovered;  // [session]
  Mesh static_mesh;
  double build_s = 0.0;
};

/// strata.io.Dataset objects as they are; a str is opened as a folder (TUM RGB-D, 7-Scenes).
std::vector<const Dataset*> datasetsFrom(const py::list& sessions,
                                         std::vector<std::unique_ptr<Dataset>>& opened) {
  std::vector<const Dataset*> out;
  for (const py::handle item : sessions) {
    if (py::isinstance<py::str>(item)) {
      opened.push_back(openDataset(item.cast<std::string>()));
      out.push_back(opened.back().get());
    } else if (py::isinstance<PyDataset>(item)) {
      out.push_back(&item.cast<const PyDataset&>().dataset());
    } else {
      throw InputError("sessions must be folders (str) or strata.io.Dataset objects, not " +
                       std::string(py::str(py::type::of(item))));
    }
  }
  if (out.size() < 2) {
    throw InputError(
        "the object database needs at least two sessions (objects are found where "
        "they moved)");
  }
  return out;
}

std::unique_ptr<PyObjectDatabase> buildDatabase(const py::list& sessions, float voxel_size_m,
                                                double recorded_per_fused, float min_weight,
                                                const py::object& device) {
  std::vector<std::unique_ptr<Dataset>> opened;
  const std::vector<const Dataset*> datasets = datasetsFrom(sessions, opened);
  if (!(min_weight > 0.0f)) throw InputError("min_weight must be > 0 (recorded frames)");
  change::ChangeConfig change_config;
  change_config.min_weight = min_weight;
  change_config = change_config.forSubsampling(recorded_per_fused);
  const MapConfig map_config = change::changeMapConfig(voxel_size_m);
  const auto context =
      PyMapper::makeContext(device.is_none() ? "" : py::str(device).cast<std::string>());
  auto out = std::make_unique<PyObjectDatabase>();
  py::gil_scoped_release release;
  DiffPipeline pipeline(*context, map_config, change_config, change::ObjectConfig{});
  std::size_t total = 0, done = 0;
  for (const Dataset* d : datasets) total += d->size();
  ProgressBar progress("objects", total, false);
  for (std::size_t i = 0; i < datasets.size(); ++i) {
    pipeline.addSession(*datasets[i], datasets[i]->name(), progress, done);
  }
  std::vector<TsdfMap> maps;
  const DiffResult result = pipeline.finish(&maps);
  const auto start = std::chrono::steady_clock::now();
  for (std::size_t s = 0; s < maps.size(); ++s) {
    const DiffSession& session = result.sessions[s];
    for (objects::SegmentOutcome& o :
         out->database.addSession(static_cast<int>(s), maps[s], session.surface, session.objects))
      out->outcomes.push_back(std::move(o));
    out->discovered.push_back(session.objects);
  }
  out->build_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  out->static_mesh = result.static_mesh;
  return out;
}

py::list instancesOf(const objects::ObjectModel& m) {
  py::list out;
  for (const objects::ObjectInstance& i : m.instances) {
    py::dict d;
    d["session"] = i.session;
    d["segment_id"] = i.segment_id;
    d["T_W_M"] = poseTo(i.T_W_M);
    d["match_score"] = i.match_score;
    d["merged"] = i.merged;
    d["pose_constrained"] = i.pose_constrained;
    out.append(d);
  }
  return out;
}

py::dict outcomeOf(const objects::SegmentOutcome& o) {
  py::dict d;
  d["session"] = o.session;
  d["segment_id"] = o.segment_id;
  d["model_id"] = o.model_id;
  d["new_model"] = o.new_model;
  d["skipped"] = o.skipped;
  d["score"] = o.score;
  d["candidates"] = o.candidates;
  d["refused"] = o.refused;
  d["joined_models"] = o.joined_models;
  return d;
}

}  // namespace

void bindObjects(py::module_& o) {
  py::class_<objects::ObjectModel>(o, "ObjectModel",
                                   "One object shape of the database and where it stood in each "
                                   "session (objects/object_model.h).")
      .def_readonly("id", &objects::ObjectModel::id, "1.. in order of creation, never reused")
      .def_readonly("merged_observations", &objects::ObjectModel::merged_observations)
      .def_property_readonly(
          "mesh", [](const objects::ObjectModel& m) { return meshTo(m.mesh_M); },
          "Its mesh in the model frame M (marching cubes of the merged TSDF)")
      .def_property_readonly(
          "instances", &instancesOf,
          "[dict(session, segment_id, T_W_M 4 x 4 model to world in that session, match_score, "
          "merged, pose_constrained)], in the order added")
      .def_property_readonly(
          "extent_m", [](const objects::ObjectModel& m) { return Eigen::Vector3f(m.extent_m); },
          "3 float32: the model's extents, sorted descending")
      .def_readonly("surface_area_m2", &objects::ObjectModel::surface_area_m2)
      .def("__repr__", [](const objects::ObjectModel& m) {
        return "ObjectModel(id=" + std::to_string(m.id) + ", " +
               std::to_string(m.instances.size()) + " instances)";
      });

  py::class_<PyObjectDatabase>(o, "ObjectDatabase", "What build() made.")
      .def_property_readonly(
          "models", [](const PyObjectDatabase& d) { return d.database.models(); }, "[ObjectModel]")
      .def_property_readonly(
          "outcomes",
          [](const PyObjectDatabase& d) {
            py::list out;
            for (const auto& o : d.outcomes) out.append(outcomeOf(o));
            return out;
          },
          "Per discovered segment of every session: dict(session, segment_id, model_id (0: "
          "skipped), new_model, skipped (why), score, candidates, refused, joined_models)")
      .def_property_readonly(
          "discovered", [](const PyObjectDatabase& d) { return d.discovered; },
          "[[strata.DiscoveredObject]] per session: the segments the database was given")
      .def_property_readonly(
          "static_mesh", [](const PyObjectDatabase& d) { return meshTo(d.static_mesh); },
          "The final static map's mesh (world frame)")
      .def(
          "session_objects",
          [](const PyObjectDatabase& d, int session) {
            return meshTo(d.database.sessionObjects(session));
          },
          py::arg("session"), "Every model placed at its instances of `session`, one mesh (world).")
      .def_readonly("build_s", &PyObjectDatabase::build_s,
                    "Wall time of the database's matching and merging (not the fusion)")
      .def("__repr__", [](const PyObjectDatabase& d) {
        return "ObjectDatabase(" + std::to_string(d.database.models().size()) + " models from " +
               std::to_string(d.outcomes.size()) + " segments)";
      });

  o.def("build", &buildDatabase, py::arg("sessions"), py::arg("voxel_size_m") = 0.05f,
        py::arg("recorded_per_fused") = 1.0, py::arg("min_weight") = 10.0f,
        py::arg("device") = py::none(),
        "The object database over sessions (oldest first; strata.io.Dataset objects such as "
        "strata.sim.session(), or folder paths), as `strata objects`: each fused into a map with "
        "change detection (MapConfig.for_change_detection(voxel_size_m)), the objects that moved "
        "discovered, matched and merged into models. recorded_per_fused: as MapperConfig's, for "
        "sessions subsampled from a 30 Hz recording; min_weight: recorded frames a voxel needs "
        "to count as observed. The GIL is released while it runs.");
}

}  // namespace strata::python
