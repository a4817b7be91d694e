#include "convert.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>
#include <sstream>

#include "strata/core/error.h"

namespace strata::python {
namespace {

std::atomic<std::size_t> input_copies{0};

/// `a` as a C-contiguous array of T: `a` itself when it is one (no copy), else a converted
/// temporary, counted by inputCopies().
template <typename T>
py::array_t<T, py::array::c_style | py::array::forcecast> inPlace(const py::array& a) {
  auto out = py::array_t<T, py::array::c_style | py::array::forcecast>::ensure(a);
  if (!out) throw py::error_already_set();
  if (out.data() != a.data()) ++input_copies;
  return out;
}

}  // namespace

std::size_t inputCopies() { return input_copies.load(); }

std::string describe(const py::array& a) {
  std::ostringstream s;
  s << "(";
  for (py::ssize_t i = 0; i < a.ndim(); ++i) s << (i ? ", " : "") << a.shape(i);
  s << (a.ndim() == 1 ? ",) " : ") ") << std::string(py::str(a.dtype()));
  return s.str();
}

void depthInto(const py::array& depth, double depth_scale, DepthImage& out) {
  if (depth.ndim() != 2) {
    throw InputError("depth must be an H x W array (float32 metres or uint16), not " +
                     describe(depth));
  }
  const bool metres = py::isinstance<py::array_t<float>>(depth);
  if (!metres && !py::isinstance<py::array_t<std::uint16_t>>(depth)) {
    throw InputError("depth must be float32 (metres) or uint16 (with depth_scale), not " +
                     describe(depth));
  }
  if (!metres && (!(depth_scale > 0.0) || !std::isfinite(depth_scale))) {
    throw InputError(
        "depth_scale must be a finite number > 0 (units per metre) for uint16 "
        "depth, not " +
        std::to_string(depth_scale));
  }
  out.height_px = static_cast<int>(depth.shape(0));
  out.width_px = static_cast<int>(depth.shape(1));
  out.depth_m.resize(static_cast<std::size_t>(depth.size()));  // keeps the buffer of a same size
  if (metres) {
    const auto d = inPlace<float>(depth);
    std::copy(d.data(), d.data() + out.depth_m.size(), out.depth_m.begin());
    return;
  }
  const auto d = inPlace<std::uint16_t>(depth);
  const std::uint16_t* p = d.data();
  for (std::size_t i = 0; i < out.depth_m.size(); ++i) {
    out.depth_m[i] = static_cast<float>(p[i] / depth_scale);
  }
}

void colorInto(const py::object& color, ColorImage& out) {
  if (color.is_none()) {
    out.width_px = out.height_px = 0;
    out.rgb.clear();
    return;
  }
  const py::array a = py::array::ensure(color);
  if (!a || a.ndim() != 3 || a.shape(2) != 3 || !py::isinstance<py::array_t<std::uint8_t>>(a)) {
    throw InputError("color must be a uint8 H x W x 3 (RGB) array, not " +
                     (a ? describe(a) : std::string("a non-array")));
  }
  const auto c = inPlace<std::uint8_t>(a);
  out.height_px = static_cast<int>(a.shape(0));
  out.width_px = static_cast<int>(a.shape(1));
  out.rgb.assign(c.data(), c.data() + a.size());
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

py::array_t<double> poseStackTo(const std::vector<std::optional<Eigen::Isometry3d>>& poses) {
  const auto n = static_cast<py::ssize_t>(poses.size());
  py::array_t<double> out({n, py::ssize_t{4}, py::ssize_t{4}});
  auto o = out.mutable_unchecked<3>();
  for (py::ssize_t i = 0; i < n; ++i) {
    const auto& T = poses[static_cast<std::size_t>(i)];
    for (int r = 0; r < 4; ++r)
      for (int c = 0; c < 4; ++c)
        o(i, r, c) = T ? T->matrix()(r, c) : std::numeric_limits<double>::quiet_NaN();
  }
  return out;
}

/// N x 3 float32 points (any float dtype is converted); every value finite.
std::vector<Eigen::Vector3f> pointsFrom(const py::array& points, const char* what) {
  if (points.ndim() != 2 || points.shape(1) != 3) {
    throw InputError(std::string(what) + " must be an N x 3 array, not " + describe(points));
  }
  const auto a = inPlace<float>(points);
  const auto p = a.unchecked<2>();
  std::vector<Eigen::Vector3f> out(static_cast<std::size_t>(points.shape(0)));
  for (std::size_t i = 0; i < out.size(); ++i) {
    const auto r = static_cast<py::ssize_t>(i);
    out[i] = Eigen::Vector3f(p(r, 0), p(r, 1), p(r, 2));
    if (!out[i].allFinite()) {
      throw InputError(std::string(what) + " row " + std::to_string(i) + " is not finite");
    }
  }
  return out;
}

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

/// Vectors as the rows of an N x 3 float64 array.
py::array_t<double> rows(const std::vector<Eigen::Vector3d>& v) {
  py::array_t<double> out({static_cast<py::ssize_t>(v.size()), py::ssize_t{3}});
  for (std::size_t i = 0; i < v.size(); ++i)
    for (int k = 0; k < 3; ++k) out.mutable_at(i, k) = v[i][k];
  return out;
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

}  // namespace strata::python
