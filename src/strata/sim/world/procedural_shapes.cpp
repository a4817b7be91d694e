#include "strata/sim/world/procedural_shapes.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "strata/core/error.h"
#include "strata/core/math_constants.h"
#include "strata/sim/rng.h"
#include "strata/sim/world/shape_mesh.h"

namespace strata::sim {
namespace {

using V3 = Eigen::Vector3d;
using Ring = std::vector<V3>;

/// Closed mesh from rings of equal size joined in order, the first closed by a fan to `start`, the
/// last by a fan to `end`. Wound outward afterwards (by the sign of its volume), so the rings'
/// direction of travel does not matter.
Mesh ringMesh(const std::vector<Ring>& rings, const V3& start, const V3& end) {
  Mesh mesh;
  const int n = static_cast<int>(rings.front().size());
  mesh.vertices.push_back(start.cast<float>());
  mesh.vertices.push_back(end.cast<float>());
  for (const Ring& ring : rings) {
    for (const V3& p : ring) mesh.vertices.push_back(p.cast<float>());
  }
  const auto at = [n](int ring, int i) { return 2 + ring * n + (i % n); };
  const int last = static_cast<int>(rings.size()) - 1;
  for (int i = 0; i < n; ++i) {
    mesh.triangles.emplace_back(0, at(0, i + 1), at(0, i));
    mesh.triangles.emplace_back(1, at(last, i), at(last, i + 1));
    for (int r = 0; r < last; ++r) {
      mesh.triangles.emplace_back(at(r, i), at(r, i + 1), at(r + 1, i + 1));
      mesh.triangles.emplace_back(at(r, i), at(r + 1, i + 1), at(r + 1, i));
    }
  }
  if (signedVolume(mesh) < 0.0) {
    for (Eigen::Vector3i& t : mesh.triangles) std::swap(t.y(), t.z());
  }
  return mesh;
}

/// Moves and scales the mesh so its bounding box is [-size/2, size/2] in x, y and [0, size.z].
void fitToSize(Mesh& mesh, const V3& size) {
  Eigen::Vector3f lo = mesh.vertices.front(), hi = lo;
  for (const Eigen::Vector3f& v : mesh.vertices) {
    lo = lo.cwiseMin(v);
    hi = hi.cwiseMax(v);
  }
  const Eigen::Vector3f extent = (hi - lo).cwiseMax(1e-9f);
  const Eigen::Vector3f s = size.cast<float>().cwiseQuotient(extent);
  const Eigen::Vector3f offset(-0.5f * size.x(), -0.5f * size.y(), 0.0f);
  for (Eigen::Vector3f& v : mesh.vertices) v = (v - lo).cwiseProduct(s) + offset;
}

/// Radius along a vase's height u in [0, 1], relative to its widest (foot, belly, neck).
std::vector<double> vaseProfile(std::uint64_t seed, int rings) {
  Rng rng(hashCombine(seed, 0x7661u));
  const double belly_at = rng.uniform(0.25, 0.6), belly_width = rng.uniform(0.18, 0.35);
  const double neck = rng.uniform(0.3, 0.6), lip = rng.uniform(0.0, 0.25);
  const double ripple = rng.uniform(0.0, 0.08), ripple_freq = rng.uniform(2.0, 5.0);
  const double phase = rng.uniform(0.0, 2.0 * kPi);
  std::vector<double> radius(rings);
  double widest = 0.0;
  for (int i = 0; i < rings; ++i) {
    const double u = static_cast<double>(i) / (rings - 1);
    const double belly = std::exp(-0.5 * std::pow((u - belly_at) / belly_width, 2.0));
    const double flare = lip * std::pow(u, 4.0);
    radius[i] = neck + (1.0 - neck) * belly + flare +
                ripple * std::sin(2.0 * kPi * ripple_freq * u + phase);
    radius[i] = std::max(radius[i], 0.2);
    widest = std::max(widest, radius[i]);
  }
  for (double& r : radius) r /= widest;
  return radius;
}

Mesh vaseMesh(const ShapeSpec& shape) {
  constexpr int kRings = 28, kSides = 40;
  const std::vector<double> profile = vaseProfile(shape.seed, kRings);
  std::vector<Ring> rings;
  for (int i = 0; i < kRings; ++i) {
    const double z = static_cast<double>(i) / (kRings - 1);
    Ring ring;
    for (int k = 0; k < kSides; ++k) {
      const double a = 2.0 * kPi * k / kSides;
      ring.emplace_back(profile[i] * std::cos(a), profile[i] * std::sin(a), z);
    }
    rings.push_back(std::move(ring));
  }
  Mesh mesh = ringMesh(rings, V3(0, 0, 0), V3(0, 0, 1));
  // The widest ring spans exactly [-1, 1] only where a side lies on an axis; fit the box anyway.
  fitToSize(mesh, shape.size_m);
  return mesh;
}

Mesh blobMesh(const ShapeSpec& shape) {
  constexpr int kRings = 24, kSides = 40, kWaves = 6;
  constexpr double kFlatBottom = 0.12;  // share of the height cut flat to stand on
  Rng rng(hashCombine(shape.seed, 0x626cu));
  V3 dir[kWaves];
  double amp[kWaves], freq[kWaves], phase[kWaves];
  for (int w = 0; w < kWaves; ++w) {
    dir[w] = V3(rng.normal(), rng.normal(), rng.normal()).normalized();
    amp[w] = rng.uniform(0.05, 0.16);
    freq[w] = rng.uniform(1.0, 3.0);
    phase[w] = rng.uniform(0.0, 2.0 * kPi);
  }
  const auto radius = [&](const V3& d) {
    double r = 1.0;
    for (int w = 0; w < kWaves; ++w) r += amp[w] * std::sin(freq[w] * dir[w].dot(d) * kPi + phase[w]);
    return std::max(r, 0.3);
  };
  const auto point = [&](double polar, double azimuth) {  // polar 0 at the bottom pole
    const V3 d(std::sin(polar) * std::cos(azimuth), std::sin(polar) * std::sin(azimuth),
               -std::cos(polar));
    return V3(radius(d) * d);
  };
  std::vector<Ring> rings;
  for (int i = 1; i < kRings; ++i) {
    Ring ring;
    for (int k = 0; k < kSides; ++k) {
      ring.push_back(point(kPi * i / kRings, 2.0 * kPi * k / kSides));
    }
    rings.push_back(std::move(ring));
  }
  V3 bottom = point(0.0, 0.0), top = point(kPi, 0.0);
  double lo = bottom.z(), hi = top.z();
  for (const Ring& ring : rings) {
    for (const V3& p : ring) {
      lo = std::min(lo, p.z());
      hi = std::max(hi, p.z());
    }
  }
  const double cut = lo + kFlatBottom * (hi - lo);
  for (Ring& ring : rings) {
    for (V3& p : ring) p.z() = std::max(p.z(), cut);
  }
  bottom.z() = std::max(bottom.z(), cut);
  Mesh mesh = ringMesh(rings, bottom, top);
  fitToSize(mesh, shape.size_m);
  return mesh;
}

Mesh tubeMesh(const ShapeSpec& shape) {
  constexpr int kSteps = 64, kSides = 20;
  constexpr double kRadius = 0.22;  // tube radius relative to the bend's
  Rng rng(hashCombine(shape.seed, 0x7475u));
  const double sweep = rng.uniform(1.0, 1.5) * kPi, start = rng.uniform(0.0, 2.0 * kPi);
  const double rise = rng.uniform(0.8, 1.6), lean = rng.uniform(-0.6, 0.6);
  const double wobble = rng.uniform(0.0, 0.2), wobble_phase = rng.uniform(0.0, 2.0 * kPi);
  const auto centre = [&](double t) {
    const double a = start + sweep * t;
    const double r = 1.0 + wobble * std::sin(2.0 * kPi * t + wobble_phase);
    const double bump = std::pow(std::sin(kPi * t), 2.0) * (1.0 + lean * (t - 0.5));
    return V3(r * std::cos(a), r * std::sin(a), kRadius + rise * bump);
  };
  std::vector<V3> c(kSteps + 1);
  for (int i = 0; i <= kSteps; ++i) c[i] = centre(static_cast<double>(i) / kSteps);
  // Parallel transport of a normal along the curve (rotation-minimising frames).
  std::vector<Ring> rings;
  V3 tangent = (c[1] - c[0]).normalized();
  V3 normal = V3::UnitZ() - V3::UnitZ().dot(tangent) * tangent;
  normal.normalize();
  for (int i = 0; i <= kSteps; ++i) {
    const V3 next_tangent =
        (i == kSteps ? c[i] - c[i - 1] : (i == 0 ? c[1] - c[0] : c[i + 1] - c[i - 1])).normalized();
    normal = (normal - normal.dot(next_tangent) * next_tangent).normalized();
    tangent = next_tangent;
    const V3 binormal = tangent.cross(normal);
    Ring ring;
    for (int k = 0; k < kSides; ++k) {
      const double a = 2.0 * kPi * k / kSides;
      ring.push_back(c[i] + kRadius * (std::cos(a) * normal + std::sin(a) * binormal));
    }
    rings.push_back(std::move(ring));
  }
  Mesh mesh = ringMesh(rings, c.front(), c.back());
  fitToSize(mesh, shape.size_m);
  return mesh;
}

double armThickness(const ShapeSpec& shape) {
  return shape.thickness_m > 0.0 ? shape.thickness_m
                                  : std::min(shape.size_m.x(), shape.size_m.y()) / 3.0;
}

std::vector<Mesh> lShapeParts(const ShapeSpec& shape) {
  const double hx = shape.size_m.x() / 2, hy = shape.size_m.y() / 2, h = shape.size_m.z();
  const double t = armThickness(shape);
  return {boxMesh(V3(-hx, -hy, 0), V3(hx, -hy + t, h)),
          boxMesh(V3(-hx, -hy + t, 0), V3(-hx + t, hy, h))};
}

std::vector<Mesh> uShapeParts(const ShapeSpec& shape) {
  const double hx = shape.size_m.x() / 2, hy = shape.size_m.y() / 2, h = shape.size_m.z();
  const double t = armThickness(shape);
  return {boxMesh(V3(-hx, -hy, 0), V3(hx, -hy + t, h)),
          boxMesh(V3(-hx, -hy + t, 0), V3(-hx + t, hy, h)),
          boxMesh(V3(hx - t, -hy + t, 0), V3(hx, hy, h))};
}

std::vector<Mesh> stoolParts(const ShapeSpec& shape) {
  const double hx = shape.size_m.x() / 2, hy = shape.size_m.y() / 2, h = shape.size_m.z();
  const double seat = std::min(0.04, 0.1 * h);
  const double leg_radius = std::min(0.015, 0.1 * std::min(hx, hy));
  std::vector<Mesh> parts;
  Mesh top = cylinderMesh(1.0, h - seat, h, 40);
  for (Eigen::Vector3f& v : top.vertices) {
    v.x() *= static_cast<float>(hx);
    v.y() *= static_cast<float>(hy);
  }
  parts.push_back(std::move(top));
  for (int k = 0; k < shape.legs; ++k) {
    const double a = 2.0 * kPi * k / shape.legs;
    const Eigen::Vector3f at(static_cast<float>((hx - 2.0 * leg_radius) * std::cos(a)),
                             static_cast<float>((hy - 2.0 * leg_radius) * std::sin(a)), 0.0f);
    Mesh leg = cylinderMesh(leg_radius, 0.0, h - seat, 8);
    for (Eigen::Vector3f& v : leg.vertices) v += at;
    parts.push_back(std::move(leg));
  }
  return parts;
}

void checkShape(const ShapeSpec& shape) {
  const std::string name = shapeKindName(shape.kind);
  if (!isProcedural(shape.kind)) throw InputError("'" + name + "' is not a procedural shape");
  if (!(shape.size_m.array() > 0.0).all()) throw InputError(name + ": every size must be positive");
  const double t = armThickness(shape);
  if (shape.kind == ShapeKind::kLShape &&
      !(t < std::min(shape.size_m.x(), shape.size_m.y()))) {
    throw InputError(name + ": thickness must be below the smaller side of the footprint");
  }
  if (shape.kind == ShapeKind::kUShape && !(2.0 * t < shape.size_m.x() && t < shape.size_m.y())) {
    throw InputError(name + ": thickness must be below half the x side and below the y side");
  }
  if (shape.kind == ShapeKind::kStool && (shape.legs < 3 || shape.legs > 8)) {
    throw InputError(name + ": legs must be 3 to 8, got " + std::to_string(shape.legs));
  }
}

}  // namespace

bool isProceduralSeeded(ShapeKind kind) {
  return kind == ShapeKind::kVase || kind == ShapeKind::kBlob || kind == ShapeKind::kTube;
}

bool isProcedural(ShapeKind kind) {
  return isProceduralSeeded(kind) || kind == ShapeKind::kLShape || kind == ShapeKind::kUShape ||
         kind == ShapeKind::kStool;
}

std::vector<Mesh> proceduralParts(const ShapeSpec& shape) {
  checkShape(shape);
  switch (shape.kind) {
    case ShapeKind::kVase:
      return {vaseMesh(shape)};
    case ShapeKind::kBlob:
      return {blobMesh(shape)};
    case ShapeKind::kTube:
      return {tubeMesh(shape)};
    case ShapeKind::kLShape:
      return lShapeParts(shape);
    case ShapeKind::kUShape:
      return uShapeParts(shape);
    case ShapeKind::kStool:
      return stoolParts(shape);
    default:
      return {};
  }
}

int proceduralYawSymmetry(const ShapeSpec& shape) {
  const bool round = std::abs(shape.size_m.x() - shape.size_m.y()) < 1e-6;
  switch (shape.kind) {
    case ShapeKind::kVase:
      return round ? 0 : 2;
    case ShapeKind::kStool:
      return round ? shape.legs : (shape.legs % 2 == 0 ? 2 : 1);
    default:
      return 1;
  }
}

double signedVolume(const Mesh& mesh) {
  double volume = 0.0;
  for (const Eigen::Vector3i& t : mesh.triangles) {
    const V3 a = mesh.vertices[t.x()].cast<double>(), b = mesh.vertices[t.y()].cast<double>(),
             c = mesh.vertices[t.z()].cast<double>();
    volume += a.dot(b.cross(c));
  }
  return volume / 6.0;
}

}  // namespace strata::sim
