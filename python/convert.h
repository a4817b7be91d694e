#pragma once
// numpy arrays to and from the C++ types, for the Python package's bindings (docs/python.md):
// depth float32 metres or uint16 with a scale, colour uint8 H x W x 3, poses 4 x 4 float64,
// points N x 3, trajectories N x 8 in TUM order. Every *From throws InputError naming the
// expected shape and dtype (or the row that is not finite) before anything is built.
// Arrays in the dtype and C order the library reads are read in place; any other is converted
// into a temporary first, which inputCopies() counts (depth, colour, points).
// Thread safety: call with the GIL held.
#include <pybind11/numpy.h>

#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "strata/core/types.h"
#include "strata/io/tum_format.h"
#include "strata/mesh/mesh.h"

namespace strata::python {

namespace py = pybind11;

/// The array's shape in words, for messages: "(480, 640) uint16".
std::string describe(const py::array& a);
/// Depth in metres from a float32 (metres) or uint16 (units of 1/depth_scale m) H x W array,
/// written into `out` (its buffer reused). NOTE: the pixels are copied once, into `out`: the
/// library's RgbdFrame owns them.
void depthInto(const py::array& depth, double depth_scale, DepthImage& out);
/// uint8 H x W x 3, or None (empty), written into `out` (its buffer reused).
void colorInto(const py::object& color, ColorImage& out);
/// Input arrays converted into a temporary (another dtype, not C-contiguous) so far in this
/// process: 0 more after a call with arrays in the library's dtype and order.
std::size_t inputCopies();
/// 4 x 4 camera to world, validated (validatePose).
Eigen::Isometry3d poseFrom(const py::array& pose, const char* what);
py::array_t<double> poseTo(const Eigen::Isometry3d& T);
/// Poses as an N x 4 x 4 float64 array; nullopt rows are NaN.
py::array_t<double> poseStackTo(const std::vector<std::optional<Eigen::Isometry3d>>& poses);
/// N x 3 (any float dtype), every value finite.
std::vector<Eigen::Vector3f> pointsFrom(const py::array& points, const char* what);

/// A mesh as arrays: vertices N x 3 float32, faces M x 3 int32, colors N x 3 uint8 (or 0 x 3),
/// normals N x 3 float32 (or 0 x 3).
struct PyMesh {
  py::array_t<float> vertices;
  py::array_t<std::int32_t> faces;
  py::array_t<std::uint8_t> colors;
  py::array_t<float> normals;
};
PyMesh meshTo(const Mesh& m);

/// Vectors as the rows of an N x 3 float64 array.
py::array_t<double> rows(const std::vector<Eigen::Vector3d>& v);
/// Timed poses as an N x 8 TUM-order array (t, x, y, z, qx, qy, qz, qw) and back.
py::array_t<double> tumArray(const std::vector<std::pair<double, Eigen::Isometry3d>>& poses);
std::vector<tum::TimedPose> timedPosesFrom(const py::array& a, const char* what);

}  // namespace strata::python
