#pragma once
// Lighting of one session: a directional light plus ambient. Sessions may change it (lights on or
// off, sun through a window), which is what change detection must tolerate.
#include <Eigen/Core>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>

#include "strata/core/error.h"

namespace strata::sim {

struct Lighting {
  /// Unit vector from a surface towards the light, world frame (z up). Default as AnalyticScene.
  Eigen::Vector3d direction_W = Eigen::Vector3d(0.3, -0.4, 1.0).normalized();
  /// Scale of the Lambert term; intensity + ambient = 1 keeps a lit albedo at its own value.
  double intensity = 0.65;
  /// Light reaching every surface regardless of orientation.
  double ambient = 0.35;

  /// Throws InputError unless direction_W is unit and intensity, ambient are finite and >= 0.
  void validate() const {
    if (!direction_W.allFinite() || std::abs(direction_W.norm() - 1.0) > 1e-6) {
      throw InputError("Lighting: direction_W must be a unit vector");
    }
    if (!(intensity >= 0.0 && ambient >= 0.0) || !std::isfinite(intensity + ambient)) {
      throw InputError("Lighting: intensity and ambient must be finite and >= 0");
    }
  }
};

/// Lambert shading factor: ambient + intensity * max(0, n . l), unclamped.
inline double shadingFactor(const Lighting& lighting, const Eigen::Vector3d& normal_W) {
  return lighting.ambient + lighting.intensity * std::max(0.0, normal_W.dot(lighting.direction_W));
}

/// albedo * shadingFactor per channel, rounded and clamped to [0, 255].
inline std::array<std::uint8_t, 3> shade(const std::array<std::uint8_t, 3>& albedo,
                                         const Lighting& lighting,
                                         const Eigen::Vector3d& normal_W) {
  const double factor = shadingFactor(lighting, normal_W);
  std::array<std::uint8_t, 3> rgb{};
  for (int c = 0; c < 3; ++c) {
    const double value = std::clamp(albedo[c] * factor, 0.0, 255.0);
    rgb[c] = static_cast<std::uint8_t>(value + 0.5);
  }
  return rgb;
}

/// Relative luminance in [0, 1] of an sRGB albedo, Rec. 709 weights on the 8-bit values.
inline double luminance(const std::array<std::uint8_t, 3>& rgb) {
  return (0.2126 * rgb[0] + 0.7152 * rgb[1] + 0.0722 * rgb[2]) / 255.0;
}

}  // namespace strata::sim
