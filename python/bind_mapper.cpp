// strata.Mapper and its configs (bindings.h): the Mapper with the device context it needs, its
// calls with numpy arrays (convert.h), the GIL released during device work.
#include <pybind11/eigen.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <memory>
#include <sstream>
#include <string>

#include "bindings.h"
#include "convert.h"
#include "py_mapper.h"
#include "strata/change/change_config.h"
#include "strata/core/error.h"
#include "strata/mapper/mapper.h"

namespace strata::python {
namespace {

template <typename T>
std::string reprOf(const char* name, const T& fields) {
  std::ostringstream s;
  s << name << "(" << fields << ")";
  return s.str();
}

}  // namespace

void bindConfigs(py::module_& m) {
  py::class_<CameraIntrinsics>(m, "CameraIntrinsics",
                               "Pinhole camera: image size (px), focal lengths and centre (px).")
      .def(py::init([](int width, int height, float fx, float fy, float cx, float cy) {
             CameraIntrinsics c{width, height, fx, fy, cx, cy};
             c.validate();
             return c;
           }),
           py::arg("width"), py::arg("height"), py::arg("fx"), py::arg("fy"), py::arg("cx"),
           py::arg("cy"))
      .def_readwrite("width", &CameraIntrinsics::width_px)
      .def_readwrite("height", &CameraIntrinsics::height_px)
      .def_readwrite("fx", &CameraIntrinsics::fx_px)
      .def_readwrite("fy", &CameraIntrinsics::fy_px)
      .def_readwrite("cx", &CameraIntrinsics::cx_px)
      .def_readwrite("cy", &CameraIntrinsics::cy_px)
      .def("validate", &CameraIntrinsics::validate,
           "Raises InputError naming a bad field (focal length, size); the constructor calls it.")
      .def("__repr__", [](const CameraIntrinsics& c) {
        std::ostringstream s;
        s << "width=" << c.width_px << ", height=" << c.height_px << ", fx=" << c.fx_px
          << ", fy=" << c.fy_px << ", cx=" << c.cx_px << ", cy=" << c.cy_px;
        return reprOf("CameraIntrinsics", s.str());
      });

  py::class_<MapConfig>(m, "MapConfig", "The TSDF map's settings (map/map_config.h).")
      .def(py::init([](float voxel_size_m, float truncation_voxels, float max_depth_m,
                       float min_depth_m, float max_weight, bool allocate_free_space) {
             MapConfig c;
             c.voxel_size_m = voxel_size_m;
             c.truncation_voxels = truncation_voxels;
             c.max_depth_m = max_depth_m;
             c.min_depth_m = min_depth_m;
             c.max_weight = max_weight;
             c.allocate_free_space = allocate_free_space;
             c.validate();
             return c;
           }),
           py::arg("voxel_size_m") = MapConfig{}.voxel_size_m,
           py::arg("truncation_voxels") = MapConfig{}.truncation_voxels,
           py::arg("max_depth_m") = MapConfig{}.max_depth_m,
           py::arg("min_depth_m") = MapConfig{}.min_depth_m,
           py::arg("max_weight") = MapConfig{}.max_weight,
           py::arg("allocate_free_space") = MapConfig{}.allocate_free_space)
      .def_readwrite("voxel_size_m", &MapConfig::voxel_size_m)
      .def_readwrite("truncation_voxels", &MapConfig::truncation_voxels)
      .def_readwrite("max_depth_m", &MapConfig::max_depth_m)
      .def_readwrite("min_depth_m", &MapConfig::min_depth_m)
      .def_readwrite("max_weight", &MapConfig::max_weight)
      .def_readwrite("allocate_free_space", &MapConfig::allocate_free_space)
      .def("validate", &MapConfig::validate,
           "Raises InputError naming a bad field (after assigning one); the constructor calls it.")
      .def_static("for_change_detection", &change::changeMapConfig, py::arg("voxel_size_m"),
                  "The map change detection compares sessions on: constant weights (a voxel's "
                  "weight counts the frames that saw it) and observed free space.")
      .def("__repr__", [](const MapConfig& c) { return reprOf("MapConfig", c.describe()); });

  py::class_<MapperConfig>(m, "MapperConfig", "What a Mapper keeps (mapper/mapper_config.h).")
      .def(py::init([](const MapConfig& map, bool esdf, bool change_detection,
                       bool keyframe_scoring, double recorded_per_fused) {
             MapperConfig c;
             c.map = map;
             c.esdf = esdf;
             c.change_detection = change_detection;
             c.keyframe_scoring = keyframe_scoring;
             c.change = c.change.forSubsampling(recorded_per_fused);
             c.map.validate();
             return c;
           }),
           py::arg("map") = MapConfig{}, py::arg("esdf") = false,
           py::arg("change_detection") = false, py::arg("keyframe_scoring") = false,
           py::arg("recorded_per_fused") = 1.0,
           "recorded_per_fused: for change detection on sessions fused from every n-th frame of "
           "a 30 Hz recording (or frames spread over a path): each fused frame stands for n views "
           "(ChangeConfig::forSubsampling).")
      .def_readwrite("map", &MapperConfig::map)
      .def_readwrite("esdf", &MapperConfig::esdf)
      .def_readwrite("change_detection", &MapperConfig::change_detection)
      .def_readwrite("keyframe_scoring", &MapperConfig::keyframe_scoring)
      .def("__repr__", [](const MapperConfig& c) {
        std::ostringstream s;
        s << "map=MapConfig(" << c.map.describe() << "), esdf=" << (c.esdf ? "True" : "False")
          << ", change_detection=" << (c.change_detection ? "True" : "False")
          << ", keyframe_scoring=" << (c.keyframe_scoring ? "True" : "False");
        return reprOf("MapperConfig", s.str());
      });
}

void bindMapper(py::module_& m) {
  py::class_<PyMesh>(m, "Mesh", "A triangle mesh as arrays (world frame, metres).")
      .def_readonly("vertices", &PyMesh::vertices, "N x 3 float32")
      .def_readonly("faces", &PyMesh::faces, "M x 3 int32, indices into vertices")
      .def_readonly("colors", &PyMesh::colors, "N x 3 uint8, or 0 x 3 without colour")
      .def_readonly("normals", &PyMesh::normals, "N x 3 float32, or 0 x 3")
      .def("__repr__", [](const PyMesh& mesh) {
        return "Mesh(" + std::to_string(mesh.vertices.shape(0)) + " vertices, " +
               std::to_string(mesh.faces.shape(0)) + " faces)";
      });

  py::class_<change::DiscoveredObject>(m, "DiscoveredObject",
                                       "An object that moved between sessions.")
      .def_readonly("id", &change::DiscoveredObject::id)
      .def_readonly("session", &change::DiscoveredObject::session)
      .def_property_readonly("centroid",
                             [](const change::DiscoveredObject& o) { return o.centroid; })
      .def_property_readonly("bbox_min",
                             [](const change::DiscoveredObject& o) { return o.bbox.min(); })
      .def_property_readonly("bbox_max",
                             [](const change::DiscoveredObject& o) { return o.bbox.max(); })
      .def_property_readonly("mesh",
                             [](const change::DiscoveredObject& o) { return meshTo(o.mesh); })
      .def("__repr__", [](const change::DiscoveredObject& o) {
        std::ostringstream s;
        s << "DiscoveredObject(id=" << o.id << ", session=" << o.session << ", centroid=["
          << o.centroid.x() << ", " << o.centroid.y() << ", " << o.centroid.z() << "])";
        return s.str();
      });

  py::class_<PyMapper>(m, "Mapper",
                       "strata::Mapper: fuse depth frames into a TSDF on the device; ESDF, mesh, "
                       "sessions with change detection, save and load (mapper/mapper.h).")
      .def(py::init([](const MapperConfig& config, const py::object& device) {
             const std::string selector =
                 device.is_none() ? "" : py::str(device).cast<std::string>();
             return std::make_unique<PyMapper>(config, selector);
           }),
           py::arg("config") = MapperConfig{}, py::arg("device") = py::none(),
           "device: None (automatic), an index or a name substring ('llvmpipe').")
      .def_static(
          "load",
          [](const std::string& path, const MapperConfig& config, const py::object& device) {
            const std::string selector =
                device.is_none() ? "" : py::str(device).cast<std::string>();
            auto context = PyMapper::makeContext(selector);
            std::unique_ptr<Mapper> mapper;
            {
              py::gil_scoped_release release;
              mapper = Mapper::load(path, *context, config);
            }
            return std::make_unique<PyMapper>(std::move(context), std::move(mapper));
          },
          py::arg("path"), py::arg("config") = MapperConfig{}, py::arg("device") = py::none(),
          "A mapper that continues from a saved .strata file (a map or a mapper's state).")
      .def(
          "integrate",
          [](PyMapper& self, const py::array& depth, const CameraIntrinsics& intrinsics,
             const py::array& T_W_C, const py::object& color, double depth_scale) {
            const Eigen::Isometry3d pose = poseFrom(T_W_C, "T_W_C");
            RgbdFrame& frame = frameFrom(self, depth, intrinsics, color, depth_scale);
            frame.T_W_C = pose;
            return withoutGil(self,
                              [&](Mapper& m) { return m.integrate(frame, intrinsics).blocks; });
          },
          py::arg("depth"), py::arg("intrinsics"), py::arg("T_W_C"), py::arg("color") = py::none(),
          py::arg("depth_scale") = 1000.0,
          "Fuses one frame at T_W_C (4 x 4, camera to world). depth: H x W float32 metres or "
          "uint16 (depth_scale units per metre); color: H x W x 3 uint8 or None. Returns the "
          "allocated block count.")
      .def(
          "track_and_integrate",
          [](PyMapper& self, const py::array& depth, const CameraIntrinsics& intrinsics,
             const py::object& color, double depth_scale) {
            const RgbdFrame& frame = frameFrom(self, depth, intrinsics, color, depth_scale);
            const TrackedFrame tracked =
                withoutGil(self, [&](Mapper& m) { return m.trackAndIntegrate(frame, intrinsics); });
            return py::make_tuple(poseTo(tracked.track.T_W_C), tracked.fused, tracked.track.reason);
          },
          py::arg("depth"), py::arg("intrinsics"), py::arg("color") = py::none(),
          py::arg("depth_scale") = 1000.0,
          "Tracks the frame against the map (no pose needed) and fuses it when tracked: "
          "(T_W_C 4 x 4, fused, reason when lost).")
      .def(
          "update_esdf",
          [](PyMapper& self) {
            return withoutGil(self, [](Mapper& m) { return m.updateEsdf().voxels_updated; });
          },
          "Brings the ESDF up to date (MapperConfig(esdf=True)); returns voxels updated.")
      .def(
          "distance",
          [](PyMapper& self, const py::array& points) {
            const std::vector<Eigen::Vector3f> p = pointsFrom(points, "points");
            const std::vector<EsdfSample> samples =
                withoutGil(self, [&](Mapper& m) { return m.distances(p); });
            const auto n = static_cast<py::ssize_t>(samples.size());
            py::array_t<float> distance(n), gradient({n, py::ssize_t{3}});
            py::array_t<bool> known(n);
            auto d = distance.mutable_unchecked<1>();
            auto g = gradient.mutable_unchecked<2>();
            auto k = known.mutable_unchecked<1>();
            for (py::ssize_t i = 0; i < n; ++i) {
              const EsdfSample& sample = samples[static_cast<std::size_t>(i)];
              d(i) = sample.distance_m;
              k(i) = sample.status == EsdfStatus::kKnown;
              for (int c = 0; c < 3; ++c) g(i, c) = sample.gradient[c];
            }
            return py::make_tuple(distance, gradient, known);
          },
          py::arg("points"),
          "ESDF at N x 3 points (after update_esdf): (distance N float32 metres, gradient N x 3, "
          "known N bool).")
      .def(
          "is_path_free",
          [](PyMapper& self, const py::array& polyline, float radius_m) {
            const std::vector<Eigen::Vector3f> p = pointsFrom(polyline, "polyline");
            return withoutGil(self, [&](Mapper& m) { return m.isPathFree(p, radius_m); });
          },
          py::arg("polyline"), py::arg("radius_m"),
          "Whether a sphere of radius_m can follow the N x 3 polyline (unknown space counts as "
          "occupied).")
      .def(
          "mesh",
          [](PyMapper& self) {
            return meshTo(withoutGil(self, [](Mapper& m) { return m.mesh(); }));
          },
          "The live layer's mesh (marching cubes) as arrays.")
      .def(
          "begin_session", [](PyMapper& self) { return self.mapper().beginSession(); },
          "Opens a session (ending an open one); returns its index.")
      .def(
          "end_session",
          [](PyMapper& self) {
            return withoutGil(self, [](Mapper& m) { return m.endSession(); }).objects;
          },
          "Ends the open session; with change detection, the objects that moved.")
      .def(
          "save",
          [](PyMapper& self, const std::string& path) {
            withoutGil(self, [&](Mapper& m) {
              m.save(path);
              return 0;
            });
          },
          py::arg("path"), "Writes the map atomically (.strata, versioned and checksummed).")
      .def("close", &PyMapper::close, "Frees the device memory now; later calls raise.")
      .def_property_readonly(
          "block_count", [](PyMapper& self) { return self.mapper().blockCount(); },
          "Allocated blocks of the map.")
      .def_property_readonly(
          "frames_integrated", [](PyMapper& self) { return self.mapper().framesIntegrated(); },
          "Frames fused so far.")
      .def_property_readonly(
          "session_count", [](PyMapper& self) { return self.mapper().sessionCount(); },
          "Sessions begun so far.")
      .def_property_readonly(
          "session_open", [](PyMapper& self) { return self.mapper().sessionOpen(); },
          "Whether a session is open.")
      .def_property_readonly(
          "config", [](PyMapper& self) { return self.mapper().config(); },
          "The MapperConfig the mapper runs with.")
      .def_property_readonly("last_call_s", &PyMapper::lastCallSeconds,
                             "Seconds the last library call of this mapper took (integrate, "
                             "distance, ...), timed in C++ around the call alone: no array "
                             "conversion, no Python. 0 before any call. For overhead "
                             "measurements (bench/python/overhead.py).");
}

}  // namespace strata::python
