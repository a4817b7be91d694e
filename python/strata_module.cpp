// The compiled part of the Python package `strata` (strata._strata): the C++ types and calls
// as they are, with numpy arrays in and out. Conventions (docs/python.md):
// - depth: float32 metres (H x W, 0 or NaN invalid) or uint16 with `depth_scale` units per
//   metre; colour: uint8 H x W x 3 (RGB); poses: 4 x 4 float64 camera to world; points N x 3.
// - C++ InputError -> strata.InputError (a ValueError), DeviceError -> strata.DeviceError, other
//   strata::Error -> strata.Error; a wrong dtype, shape or a non-finite value names what was
//   expected before any work.
// - The GIL is released during device work (integrate, ESDF updates, queries, meshing, saving),
//   so other Python threads run meanwhile; one Mapper must not be used by two threads at once.
#include <pybind11/eigen.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <cmath>
#include <memory>
#include <sstream>
#include <string>

#include "strata/change/change_config.h"
#include "strata/core/error.h"
#include "strata/core/types.h"
#include "strata/io/euroc_dataset.h"
#include "strata/io/open_dataset.h"
#include "strata/map/map_file.h"
#include "strata/mapper/mapper.h"
#include "strata/mesh/mesh.h"
#include "strata/odometry/pipeline/vio_pipeline.h"
#include "strata/odometry/pipeline/vio_replay.h"
#include "strata/sim/sim_setup.h"
#include "strata/sim/world/world_paths.h"
#include "strata/trajectory/trajectory_error.h"
#include "strata/vk/vk.h"

namespace py = pybind11;

namespace strata::python {
namespace {

using FloatArray = py::array_t<float, py::array::c_style | py::array::forcecast>;

/// The array's shape in words, for messages: "(480, 640) uint16".
std::string describe(const py::array& a) {
  std::ostringstream s;
  s << "(";
  for (py::ssize_t i = 0; i < a.ndim(); ++i) s << (i ? ", " : "") << a.shape(i);
  s << (a.ndim() == 1 ? ",) " : ") ") << std::string(py::str(a.dtype()));
  return s.str();
}

/// Depth in metres from a float32 (metres) or uint16 (units of 1/depth_scale m) H x W array.
DepthImage depthFrom(const py::array& depth, double depth_scale) {
  if (depth.ndim() != 2) {
    throw InputError("depth must be an H x W array (float32 metres or uint16), not " +
                     describe(depth));
  }
  const int h = static_cast<int>(depth.shape(0)), w = static_cast<int>(depth.shape(1));
  DepthImage out(w, h);
  if (py::isinstance<py::array_t<std::uint16_t>>(depth)) {
    if (!(depth_scale > 0.0) || !std::isfinite(depth_scale)) {
      throw InputError(
          "depth_scale must be a finite number > 0 (units per metre) for uint16 "
          "depth, not " +
          std::to_string(depth_scale));
    }
    const auto d = py::array_t<std::uint16_t, py::array::c_style | py::array::forcecast>(depth);
    const std::uint16_t* p = d.data();
    for (std::size_t i = 0; i < out.depth_m.size(); ++i) {
      out.depth_m[i] = static_cast<float>(p[i] / depth_scale);
    }
    return out;
  }
  if (!py::isinstance<py::array_t<float>>(depth)) {
    throw InputError("depth must be float32 (metres) or uint16 (with depth_scale), not " +
                     describe(depth));
  }
  const FloatArray d(depth);
  std::copy(d.data(), d.data() + out.depth_m.size(), out.depth_m.begin());
  return out;
}

ColorImage colorFrom(const py::object& color) {
  if (color.is_none()) return {};
  const py::array a = py::array::ensure(color);
  if (!a || a.ndim() != 3 || a.shape(2) != 3 || !py::isinstance<py::array_t<std::uint8_t>>(a)) {
    throw InputError("color must be a uint8 H x W x 3 (RGB) array, not " +
                     (a ? describe(a) : std::string("a non-array")));
  }
  const auto c = py::array_t<std::uint8_t, py::array::c_style | py::array::forcecast>(a);
  ColorImage out(static_cast<int>(a.shape(1)), static_cast<int>(a.shape(0)));
  std::copy(c.data(), c.data() + out.rgb.size(), out.rgb.begin());
  return out;
}

Eigen::Isometry3d poseFrom(const py::array& pose, const char* what) {
  if (pose.ndim() != 2 || pose.shape(0) != 4 || pose.shape(1) != 4) {
    throw InputError(std::string(what) + " must be a 4 x 4 array (camera to world), not " +
                     describe(pose));
  }
  const auto m = py::array_t<double, py::array::c_style | py::array::forcecast>(pose);
  Eigen::Matrix4d T;
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c) T(r, c) = m.at(r, c);
  Eigen::Isometry3d out;
  out.matrix() = T;
  validatePose(out, what);
  return out;
}

py::array_t<double> poseTo(const Eigen::Isometry3d& T) {
  py::array_t<double> out({4, 4});
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c) out.mutable_at(r, c) = T.matrix()(r, c);
  return out;
}

/// N x 3 float32 points (any float dtype is converted); every value finite.
std::vector<Eigen::Vector3f> pointsFrom(const py::array& points, const char* what) {
  if (points.ndim() != 2 || points.shape(1) != 3) {
    throw InputError(std::string(what) + " must be an N x 3 array, not " + describe(points));
  }
  const FloatArray p(points);
  std::vector<Eigen::Vector3f> out(static_cast<std::size_t>(points.shape(0)));
  for (std::size_t i = 0; i < out.size(); ++i) {
    out[i] = Eigen::Vector3f(p.at(i, 0), p.at(i, 1), p.at(i, 2));
    if (!out[i].allFinite()) {
      throw InputError(std::string(what) + " row " + std::to_string(i) + " is not finite");
    }
  }
  return out;
}

/// A mesh as arrays: vertices N x 3 float32, faces M x 3 int32, colors N x 3 uint8 (or empty),
/// normals N x 3 float32 (or empty).
struct PyMesh {
  py::array_t<float> vertices;
  py::array_t<std::int32_t> faces;
  py::array_t<std::uint8_t> colors;
  py::array_t<float> normals;
};

PyMesh meshTo(const Mesh& m) {
  PyMesh out;
  const auto n = static_cast<py::ssize_t>(m.vertices.size());
  out.vertices = py::array_t<float>({n, py::ssize_t{3}});
  out.normals = py::array_t<float>({m.hasNormals() ? n : 0, py::ssize_t{3}});
  out.colors = py::array_t<std::uint8_t>({m.hasColors() ? n : 0, py::ssize_t{3}});
  out.faces =
      py::array_t<std::int32_t>({static_cast<py::ssize_t>(m.triangles.size()), py::ssize_t{3}});
  for (py::ssize_t i = 0; i < n; ++i) {
    for (int k = 0; k < 3; ++k) {
      out.vertices.mutable_at(i, k) = m.vertices[i][k];
      if (m.hasNormals()) out.normals.mutable_at(i, k) = m.normals[i][k];
      if (m.hasColors()) out.colors.mutable_at(i, k) = m.colors[i][k];
    }
  }
  for (std::size_t t = 0; t < m.triangles.size(); ++t)
    for (int k = 0; k < 3; ++k) out.faces.mutable_at(t, k) = m.triangles[t][k];
  return out;
}

/// A Mapper with the device context it needs (the context outlives the mapper).
class PyMapper {
 public:
  PyMapper(const MapperConfig& config, const std::string& device) : context_(makeContext(device)) {
    mapper_ = std::make_unique<Mapper>(config, *context_);
  }
  PyMapper(std::unique_ptr<vk::Context> context, std::unique_ptr<Mapper> mapper)
      : context_(std::move(context)), mapper_(std::move(mapper)) {}

  static std::unique_ptr<vk::Context> makeContext(const std::string& device) {
    vk::ContextOptions options;
    options.device_selector = device;
    options.log_device = false;
    return vk::Context::create(options);
  }

  Mapper& mapper() {
    if (!mapper_) throw InputError("the mapper is closed");
    return *mapper_;
  }
  void close() {
    mapper_.reset();
    context_.reset();
  }

 private:
  std::unique_ptr<vk::Context> context_;
  std::unique_ptr<Mapper> mapper_;
};

/// `work(mapper)` with the GIL released (other Python threads run meanwhile); its result is
/// returned once the GIL is held again.
template <typename Work>
auto withoutGil(PyMapper& self, Work work) {
  Mapper& mapper = self.mapper();
  py::gil_scoped_release release;
  return work(mapper);
}

RgbdFrame frameFrom(const py::array& depth, const CameraIntrinsics& intrinsics,
                    const py::object& color, double depth_scale) {
  RgbdFrame frame;
  frame.depth = depthFrom(depth, depth_scale);
  frame.color = colorFrom(color);
  validateFrame(frame, intrinsics);
  return frame;
}

template <typename T>
std::string reprOf(const char* name, const T& fields) {
  std::ostringstream s;
  s << name << "(" << fields << ")";
  return s.str();
}

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
      .def("validate", &CameraIntrinsics::validate)
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
      .def("validate", &MapConfig::validate)
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
            RgbdFrame frame = frameFrom(depth, intrinsics, color, depth_scale);
            frame.T_W_C = poseFrom(T_W_C, "T_W_C");
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
            const RgbdFrame frame = frameFrom(depth, intrinsics, color, depth_scale);
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
            for (py::ssize_t i = 0; i < n; ++i) {
              distance.mutable_at(i) = samples[i].distance_m;
              known.mutable_at(i) = samples[i].status == EsdfStatus::kKnown;
              for (int k = 0; k < 3; ++k) gradient.mutable_at(i, k) = samples[i].gradient[k];
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
      .def_property_readonly("block_count",
                             [](PyMapper& self) { return self.mapper().blockCount(); })
      .def_property_readonly("frames_integrated",
                             [](PyMapper& self) { return self.mapper().framesIntegrated(); })
      .def_property_readonly("session_count",
                             [](PyMapper& self) { return self.mapper().sessionCount(); })
      .def_property_readonly("session_open",
                             [](PyMapper& self) { return self.mapper().sessionOpen(); })
      .def_property_readonly("config", [](PyMapper& self) { return self.mapper().config(); });
}

/// A dataset folder (TUM RGB-D, 7-Scenes) as a sequence of frames.
class PyDataset {
 public:
  explicit PyDataset(const std::string& path) : dataset_(openDataset(path)) {}
  explicit PyDataset(std::unique_ptr<Dataset> dataset) : dataset_(std::move(dataset)) {}
  std::size_t size() const { return dataset_->size(); }
  CameraIntrinsics intrinsics() const { return dataset_->intrinsics(); }
  std::string name() const { return dataset_->name(); }
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

void bindIo(py::module_& io) {
  py::class_<PyDataset>(io, "Dataset",
                        "A TUM RGB-D or 7-Scenes folder: len(), [i] -> dict(depth float32 "
                        "metres H x W, color uint8 H x W x 3 or None, T_W_C 4 x 4, timestamp_s, "
                        "name), intrinsics.")
      .def(py::init<const std::string&>(), py::arg("path"))
      .def("__len__", &PyDataset::size)
      .def("__getitem__", &PyDataset::frame, py::arg("index"))
      .def_property_readonly("intrinsics", &PyDataset::intrinsics)
      .def_property_readonly("name", &PyDataset::name)
      .def_property_readonly("recorded_frames", &PyDataset::recordedFrames,
                             "Frames of the whole recording (a simulated path at its rate)")
      .def("__repr__", [](const PyDataset& d) {
        return "Dataset(" + d.name() + ", " + std::to_string(d.size()) + " frames)";
      });
}

/// N x 8 (t, x, y, z, qx, qy, qz, qw) -> timed poses.
std::vector<tum::TimedPose> timedPosesFrom(const py::array& a, const char* what) {
  if (a.ndim() != 2 || a.shape(1) != 8) {
    throw InputError(std::string(what) +
                     " must be an N x 8 array (t, x, y, z, qx, qy, qz, qw: "
                     "TUM order), not " +
                     describe(a));
  }
  const auto m = py::array_t<double, py::array::c_style | py::array::forcecast>(a);
  std::vector<tum::TimedPose> out(static_cast<std::size_t>(a.shape(0)));
  for (std::size_t i = 0; i < out.size(); ++i) {
    for (int k = 0; k < 8; ++k) {
      if (!std::isfinite(m.at(i, k))) {
        throw InputError(std::string(what) + " row " + std::to_string(i) + " is not finite");
      }
    }
    out[i].timestamp_s = m.at(i, 0);
    const Eigen::Quaterniond q(m.at(i, 7), m.at(i, 4), m.at(i, 5), m.at(i, 6));
    if (q.norm() < 1e-9)
      throw InputError(std::string(what) + " row " + std::to_string(i) + " has a zero quaternion");
    out[i].T_W_C.linear() = q.normalized().toRotationMatrix();
    out[i].T_W_C.translation() = Eigen::Vector3d(m.at(i, 1), m.at(i, 2), m.at(i, 3));
  }
  return out;
}

/// Vectors as the rows of an N x 3 float64 array.
py::array_t<double> rows(const std::vector<Eigen::Vector3d>& v) {
  py::array_t<double> out({static_cast<py::ssize_t>(v.size()), py::ssize_t{3}});
  for (std::size_t i = 0; i < v.size(); ++i)
    for (int k = 0; k < 3; ++k) out.mutable_at(i, k) = v[i][k];
  return out;
}

void bindTrajectory(py::module_& t) {
  py::class_<trajectory::TrajectoryError>(t, "TrajectoryError",
                                          "ATE and RPE of an estimate against the truth.")
      .def_readonly("matched", &trajectory::TrajectoryError::matched)
      .def_readonly("ate_rmse_m", &trajectory::TrajectoryError::ate_rmse_m)
      .def_readonly("ate_max_m", &trajectory::TrajectoryError::ate_max_m)
      .def_readonly("path_length_m", &trajectory::TrajectoryError::path_length_m)
      .def_readonly("rpe_trans_percent", &trajectory::TrajectoryError::rpe_trans_percent)
      .def_readonly("rpe_rot_deg_per_m", &trajectory::TrajectoryError::rpe_rot_deg_per_m)
      .def_readonly("scale", &trajectory::TrajectoryError::scale)
      .def_property_readonly(
          "aligned_positions",
          [](const trajectory::TrajectoryError& e) { return rows(e.estimate_positions_m); },
          "N x 3: the matched estimate positions after the alignment")
      .def_property_readonly(
          "truth_positions",
          [](const trajectory::TrajectoryError& e) { return rows(e.truth_positions_m); },
          "N x 3: the truth positions they were matched to")
      .def("__repr__", [](const trajectory::TrajectoryError& e) {
        std::ostringstream s;
        s << "TrajectoryError(matched=" << e.matched << ", ate_rmse_m=" << e.ate_rmse_m
          << ", ate_max_m=" << e.ate_max_m << ", path_length_m=" << e.path_length_m << ")";
        return s.str();
      });
  t.def(
      "evaluate",
      [](const py::array& estimate, const py::array& truth, const std::string& alignment) {
        trajectory::Alignment a;
        if (alignment == "se3") {
          a = trajectory::Alignment::kSE3;
        } else if (alignment == "sim3") {
          a = trajectory::Alignment::kSim3;
        } else {
          throw InputError("alignment must be 'se3' or 'sim3', not '" + alignment + "'");
        }
        return trajectory::evaluateTrajectory(timedPosesFrom(estimate, "estimate"),
                                              timedPosesFrom(truth, "truth"), a);
      },
      py::arg("estimate"), py::arg("truth"), py::arg("alignment") = "se3",
      "ATE/RPE of N x 8 TUM-order arrays (t, x, y, z, qx, qy, qz, qw), matched by time.");
}

/// Poses as an N x 8 TUM-order array (t, x, y, z, qx, qy, qz, qw).
py::array_t<double> tumArray(const std::vector<std::pair<double, Eigen::Isometry3d>>& poses) {
  py::array_t<double> out({static_cast<py::ssize_t>(poses.size()), py::ssize_t{8}});
  for (std::size_t i = 0; i < poses.size(); ++i) {
    const Eigen::Isometry3d& T = poses[i].second;
    const Eigen::Quaterniond q(T.rotation());
    const double row[8] = {poses[i].first,
                           T.translation().x(),
                           T.translation().y(),
                           T.translation().z(),
                           q.x(),
                           q.y(),
                           q.z(),
                           q.w()};
    for (int k = 0; k < 8; ++k) out.mutable_at(i, k) = row[k];
  }
  return out;
}

/// A VIO run over an EuRoC folder: the left camera's trajectory and the pipeline's counts.
struct VioRun {
  bool stereo = true;
  py::array_t<double> trajectory;  // N x 8, tracked frames
  py::array_t<double> truth;       // M x 8, the left camera's truth (0 x 8 without)
  std::size_t frames_processed = 0;
  std::size_t frames_tracked = 0;
  std::vector<std::pair<double, std::string>> failures;  // (t_s, reason)
  std::size_t imu_out_of_range = 0;
  double wall_s = 0.0;
};

VioRun runEuroc(const std::string& folder, bool mono, std::size_t frames, int window) {
  euroc::ReaderOptions reader;
  reader.use_right_camera = !mono;
  const euroc::EurocDataset dataset = euroc::EurocDataset::open(folder, reader);
  if (!mono && !dataset.stereo()) {
    throw InputError(folder +
                     ": the session has no right camera: stereo VIO needs it; pass "
                     "mono=True to run on cam0 alone");
  }
  odometry::VioPipelineConfig config;
  config.mono = mono;
  config.backend.window_size = window;
  config.validate();
  odometry::ReplayInput input;
  input.imu = &dataset.imu();
  for (const auto& f : dataset.frames()) input.frame_timestamps_ns.push_back(f.timestamp_ns);
  input.load = [&](std::size_t k) { return dataset.loadImages(k); };
  input.max_frames = frames;
  odometry::ReplayResult result;
  {
    py::gil_scoped_release release;
    odometry::VioPipeline pipeline(dataset.calibration(), config);
    result = odometry::replayVio(pipeline, input);
  }
  VioRun run;
  run.stereo = result.stereo;
  std::vector<std::pair<double, Eigen::Isometry3d>> poses, truth;
  for (const auto& f : result.tracked) poses.emplace_back(1e-9 * f.timestamp_ns, f.T_W_C);
  const Eigen::Isometry3d& T_B_C = dataset.calibration().cameras.at(0).T_B_C;
  for (const auto& g : dataset.groundTruth())
    truth.emplace_back(1e-9 * g.timestamp_ns, g.T_W_B * T_B_C);
  run.trajectory = tumArray(poses);
  run.truth = tumArray(truth);
  run.frames_processed = result.stats.frames_processed;
  run.frames_tracked = result.stats.frames_tracking;
  for (const auto& [t_ns, reason] : result.stats.failure_log)
    run.failures.emplace_back(1e-9 * t_ns, reason);
  run.imu_out_of_range = result.stats.imu_out_of_range_skipped;
  run.wall_s = result.wall_s;
  return run;
}

void bindSim(py::module_& s) {
  s.def(
      "session",
      [](const std::string& world, int session, int frames, double rate_hz, bool noise) {
        const auto loaded = sim::loadWorld(sim::findWorld(world), 0, 0);
        if (frames < 0) throw InputError("frames must be >= 0 (0: every frame of the path)");
        auto dataset = std::make_unique<sim::SimSessionDataset>(
            loaded, session, sim::sessionConfig(rate_hz, frames, noise, false));
        return std::make_unique<PyDataset>(std::move(dataset));
      },
      py::arg("world") = "room", py::arg("session") = 0, py::arg("frames") = 30,
      py::arg("rate_hz") = 30.0, py::arg("noise") = true,
      "A simulated session of a world (a shipped name: room, office, warehouse, deadend, or a "
      "world file) as a Dataset: `frames` frames spread over the session's path (0: all at "
      "rate_hz), rendered when indexed, with the simulator's depth noise unless noise=False.");
}

void bindOdometry(py::module_& o) {
  py::class_<VioRun>(o, "VioRun", "What run_euroc gives: the left camera's trajectory and counts.")
      .def_readonly("stereo", &VioRun::stereo)
      .def_readonly("trajectory", &VioRun::trajectory,
                    "N x 8 (t, x, y, z, qx, qy, qz, qw): the tracked frames' left camera to world")
      .def_readonly("truth", &VioRun::truth, "M x 8: the left camera's truth (0 x 8 without)")
      .def_readonly("frames_processed", &VioRun::frames_processed)
      .def_readonly("frames_tracked", &VioRun::frames_tracked)
      .def_readonly("failures", &VioRun::failures, "[(t_s, reason)]")
      .def_readonly("imu_out_of_range", &VioRun::imu_out_of_range)
      .def_readonly("wall_s", &VioRun::wall_s)
      .def("__repr__", [](const VioRun& r) {
        return "VioRun(" + std::string(r.stereo ? "stereo" : "mono") + ", " +
               std::to_string(r.frames_tracked) + " of " + std::to_string(r.frames_processed) +
               " frames tracked, " + std::to_string(r.failures.size()) + " failures)";
      });
  o.def("run_euroc", &runEuroc, py::arg("folder"), py::arg("mono") = false, py::arg("frames") = 0,
        py::arg("window") = 10,
        "Visual-inertial odometry over an EuRoC/ASL folder (mav0/), as `strata odometry`: "
        "frames > 0 processes only the first frames. The GIL is released while it runs.");
}

}  // namespace
}  // namespace strata::python

PYBIND11_MODULE(_strata, m) {
  using namespace strata;
  using namespace strata::python;
  m.doc() = "Strata: dense multi-session mapping (the C++ library's types and calls)";
  static py::exception<Error> error(m, "Error", PyExc_RuntimeError);
  static py::exception<InputError> input_error(m, "InputError", PyExc_ValueError);
  static py::exception<DeviceError> device_error(m, "DeviceError", error.ptr());
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
  py::module_ io = m.def_submodule("io", "Datasets as arrays");
  bindIo(io);
  py::module_ trajectory = m.def_submodule("trajectory", "Trajectory accuracy (ATE, RPE)");
  bindTrajectory(trajectory);
  py::module_ sim = m.def_submodule("sim", "The simulator's worlds and sessions");
  bindSim(sim);
  py::module_ odometry = m.def_submodule("odometry", "Visual-inertial odometry");
  bindOdometry(odometry);
  m.def("validation_errors", &vk::validationErrorCount,
        "Vulkan validation errors reported so far in this process (STRATA_VALIDATION=1 turns the "
        "layer on); tests assert 0.");
}
