#include "strata/track/photometric.h"

#include <algorithm>
#include <cmath>

namespace strata {

IntensityImage intensityOf(const ColorImage& color) {
  IntensityImage out{color.width_px, color.height_px, {}};
  out.value.resize(static_cast<std::size_t>(color.width_px) * color.height_px);
  for (std::size_t i = 0; i < out.value.size(); ++i) {
    const std::uint8_t* p = &color.rgb[i * 3];
    out.value[i] = (static_cast<float>(p[0]) + p[1] + p[2]) / (3.0f * 255.0f);
  }
  return out;
}

IntensityImage halfIntensity(const IntensityImage& image) {
  IntensityImage out{image.width_px / 2, image.height_px / 2, {}};
  out.value.resize(static_cast<std::size_t>(out.width_px) * out.height_px);
  for (int v = 0; v < out.height_px; ++v) {
    for (int u = 0; u < out.width_px; ++u) {
      const std::size_t i = static_cast<std::size_t>(2 * v) * image.width_px + 2 * u;
      out.value[static_cast<std::size_t>(v) * out.width_px + u] =
          0.25f * (image.value[i] + image.value[i + 1] + image.value[i + image.width_px] +
                   image.value[i + image.width_px + 1]);
    }
  }
  return out;
}

IntensityModel intensityModel(const RaycastImage& raycast, const CameraIntrinsics& intrinsics,
                              const Eigen::Isometry3d& T_W_M) {
  IntensityModel m;
  m.intrinsics = intrinsics;
  m.T_W_M = T_W_M;
  m.intensity = intensityOf(raycast.color);
  m.depth_m = raycast.depth.depth_m;
  const int w = intrinsics.width_px, h = intrinsics.height_px;
  m.grad_u.assign(m.depth_m.size(), 0.0f);
  m.grad_v.assign(m.depth_m.size(), 0.0f);
  for (int v = 1; v + 1 < h; ++v) {
    for (int u = 1; u + 1 < w; ++u) {
      const std::size_t i = static_cast<std::size_t>(v) * w + u;
      if (!raycast.hit[i - 1] || !raycast.hit[i + 1] || !raycast.hit[i - w] || !raycast.hit[i + w])
        continue;
      m.grad_u[i] = 0.5f * (m.intensity.value[i + 1] - m.intensity.value[i - 1]);
      m.grad_v[i] = 0.5f * (m.intensity.value[i + w] - m.intensity.value[i - w]);
    }
  }
  return m;
}

namespace {

// Four model pixels whose depths spread over more than this share of the nearest lie across a
// depth edge.
constexpr float kMaxEdgeShare = 0.02f;

/// The four model pixels around (u, v) and their bilinear weights; false when one rendered no
/// surface, lies outside the image's interior, or a depth edge runs between them (the colour
/// there blends two surfaces).
struct Footprint {
  std::size_t i = 0;  // top-left pixel
  float w00 = 0, w10 = 0, w01 = 0, w11 = 0;
  float sample(const std::vector<float>& values, int width) const {
    return w00 * values[i] + w10 * values[i + 1] + w01 * values[i + width] +
           w11 * values[i + width + 1];
  }
};

bool footprint(const IntensityModel& m, float u, float v, Footprint* out) {
  const int w = m.intrinsics.width_px, h = m.intrinsics.height_px;
  const int u0 = static_cast<int>(std::floor(u)), v0 = static_cast<int>(std::floor(v));
  if (u0 < 1 || v0 < 1 || u0 + 2 >= w || v0 + 2 >= h) return false;
  const std::size_t i = static_cast<std::size_t>(v0) * w + u0;
  const float z[4] = {m.depth_m[i], m.depth_m[i + 1], m.depth_m[i + w], m.depth_m[i + w + 1]};
  const float z_min = std::min(std::min(z[0], z[1]), std::min(z[2], z[3]));
  const float z_max = std::max(std::max(z[0], z[1]), std::max(z[2], z[3]));
  if (z_min <= 0.0f || z_max - z_min > kMaxEdgeShare * z_min) return false;
  const float a = u - u0, b = v - v0;
  *out = Footprint{i, (1 - a) * (1 - b), a * (1 - b), (1 - a) * b, a * b};
  return true;
}

}  // namespace

NormalEquations photometricEquations(const LiveLevel& live, const IntensityImage& intensity,
                                     const IntensityModel& model, const Eigen::Isometry3d& T_W_C,
                                     const PhotometricGates& gates) {
  NormalEquations sums;
  struct Row {
    Eigen::Matrix<double, 6, 1> J;
    double r = 0.0;
  };
  std::vector<Row> rows;
  const Eigen::Isometry3d T_M_C = model.T_W_M.inverse() * T_W_C;
  const Eigen::Matrix3d R_M_C = T_M_C.rotation();
  const CameraIntrinsics& K = model.intrinsics;
  for (std::size_t p = 0; p < live.vertex_C.size(); ++p) {
    const Eigen::Vector4f& v4 = live.vertex_C[p];
    // A live pixel without a normal lies at a depth edge (its colour is either side's).
    if (v4.w() < 0.5f || live.normal_C[p].w() < 0.5f) continue;
    const Eigen::Vector3d p_C = v4.head<3>().cast<double>();
    const Eigen::Vector3d p_M = T_M_C * p_C;
    if (p_M.z() <= 1e-3) continue;
    const double u = K.fx_px * p_M.x() / p_M.z() + K.cx_px;
    const double v = K.fy_px * p_M.y() / p_M.z() + K.cy_px;
    Footprint f;
    if (!footprint(model, static_cast<float>(u), static_cast<float>(v), &f)) continue;
    const int width = K.width_px;
    if (std::fabs(f.sample(model.depth_m, width) - p_M.z()) > gates.max_distance_m) continue;
    const float gu = f.sample(model.grad_u, width), gv = f.sample(model.grad_v, width);
    if (std::hypot(gu, gv) < gates.min_gradient) continue;
    const float I_M = f.sample(model.intensity.value, width);
    const double r = static_cast<double>(I_M) - intensity.value[p];
    // d pi / d p_M, times the gradient: a = (gu, gv) J_pi.
    const double iz = 1.0 / p_M.z();
    const Eigen::Vector3d a(gu * K.fx_px * iz, gv * K.fy_px * iz,
                            -(gu * K.fx_px * p_M.x() + gv * K.fy_px * p_M.y()) * iz * iz);
    const Eigen::Vector3d b = R_M_C.transpose() * a;
    Row row;
    row.J << b, p_C.cross(b);
    row.r = r;
    rows.push_back(row);
  }
  if (rows.empty()) return sums;
  // The two images' brightness may differ by an offset (exposure, the voxels' blended colour):
  // the residuals are taken about their median, so only the pattern's displacement counts.
  std::vector<double> residuals;
  residuals.reserve(rows.size());
  for (const Row& row : rows) residuals.push_back(row.r);
  std::nth_element(residuals.begin(), residuals.begin() + residuals.size() / 2, residuals.end());
  const double offset = residuals[residuals.size() / 2];
  for (const Row& row : rows) {
    const double r = row.r - offset;
    const double weight =
        gates.huber > 0.0f && std::fabs(r) > gates.huber ? gates.huber / std::fabs(r) : 1.0;
    int k = 0;
    for (int i = 0; i < 6; ++i) {
      for (int j = i; j < 6; ++j) sums.JtJ[k++] += weight * row.J[i] * row.J[j];
      sums.Jtr[i] += weight * row.J[i] * r;
    }
    sums.residual_sq += r * r;
    ++sums.inliers;
  }
  return sums;
}

NormalEquations addWeighted(const NormalEquations& a, const NormalEquations& b, double weight) {
  NormalEquations out = a;
  const double w2 = weight * weight;
  for (std::size_t i = 0; i < out.JtJ.size(); ++i) out.JtJ[i] += w2 * b.JtJ[i];
  for (std::size_t i = 0; i < out.Jtr.size(); ++i) out.Jtr[i] += w2 * b.Jtr[i];
  out.residual_sq += w2 * b.residual_sq;
  return out;
}

}  // namespace strata
