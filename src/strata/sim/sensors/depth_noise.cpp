#include "strata/sim/sensors/depth_noise.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "strata/core/error.h"
#include "strata/core/math_constants.h"

namespace strata::sim {
namespace {

constexpr double kDegToRad = kPi / 180.0;
constexpr double kMaxAngleTermRad = 85.0 * kDegToRad;  // NOTE: theta^2 / (pi/2 - theta)^2 -> inf

void requireNonNegative(double value, const char* field) {
  if (!(value >= 0.0) || !std::isfinite(value)) {
    throw InputError(std::string("DepthNoiseConfig: ") + field + " must be finite and >= 0");
  }
}

void requireProbability(double value, const char* field) {
  if (!(value >= 0.0 && value <= 1.0)) {
    throw InputError(std::string("DepthNoiseConfig: ") + field + " must lie in [0, 1]");
  }
}

// Hermite smoothstep: 0 below 0, 1 above 1, C1 in between.
double smoothstep(double x) {
  x = std::clamp(x, 0.0, 1.0);
  return x * x * (3.0 - 2.0 * x);
}

bool dropped(bool effect_on, bool applies, double probability, double draw) {
  return effect_on && applies && draw < probability;
}

}  // namespace

void DepthNoiseConfig::validate() const {
  requireNonNegative(axial_a_m, "axial_a_m");
  requireNonNegative(axial_b_per_m, "axial_b_per_m");
  requireNonNegative(axial_z0_m, "axial_z0_m");
  requireNonNegative(axial_angle_m, "axial_angle_m");
  if (!(grazing_start_deg >= 0.0 && grazing_start_deg < grazing_full_deg &&
        grazing_full_deg <= 90.0)) {
    throw InputError(
        "DepthNoiseConfig: grazing_start_deg/grazing_full_deg need 0 <= start < full <= 90");
  }
  requireProbability(dark_luminance_max, "dark_luminance_max");
  requireProbability(dark_dropout_probability, "dark_dropout_probability");
  requireProbability(reflectivity_min, "reflectivity_min");
  requireProbability(reflective_dropout_probability, "reflective_dropout_probability");
  requireNonNegative(flying_min_jump_m, "flying_min_jump_m");
  requireProbability(flying_pixel_probability, "flying_pixel_probability");
}

DepthPixelDraws DepthPixelDraws::draw(Rng& rng) {
  DepthPixelDraws d;
  d.flying = rng.uniform();
  d.flying_mix = rng.uniform();
  d.grazing = rng.uniform();
  d.dark = rng.uniform();
  d.reflective = rng.uniform();
  d.normal_u1 = rng.uniform();
  d.normal_u2 = rng.uniform();
  return d;
}

double axialSigma(const DepthNoiseConfig& c, double z_m, double incidence_rad) {
  // Nguyen et al. 2012: 0.0012 + 0.0019 (z - 0.4)^2 + 0.0001 / sqrt(z) * theta^2 / (pi/2 - theta)^2
  const double theta = std::clamp(incidence_rad, 0.0, kMaxAngleTermRad);
  const double dz = z_m - c.axial_z0_m;
  const double angle_ratio = theta / (0.5 * kPi - theta);
  return c.axial_a_m + c.axial_b_per_m * dz * dz +
         c.axial_angle_m / std::sqrt(std::max(z_m, 1e-6)) * angle_ratio * angle_ratio;
}

double grazingDropProbability(const DepthNoiseConfig& c, double incidence_rad) {
  const double start = c.grazing_start_deg * kDegToRad;
  const double full = c.grazing_full_deg * kDegToRad;
  return smoothstep((incidence_rad - start) / (full - start));
}

float applyDepthNoise(const DepthNoiseConfig& c, const DepthPixel& pixel,
                      const DepthPixelDraws& draws) {
  double z = pixel.z_true_m;
  if (!c.enabled || z <= 0.0) return static_cast<float>(z);
  // Mixed pixel: a depth between the two surfaces, z + w (z_other - z), w ~ U(0, 1).
  if (c.flying_pixels && pixel.z_across_edge_m > 0.0f &&
      draws.flying < c.flying_pixel_probability) {
    z += draws.flying_mix * (pixel.z_across_edge_m - z);
  }
  const double incidence =
      std::acos(std::clamp(static_cast<double>(pixel.cos_incidence), 0.0, 1.0));
  if (dropped(c.grazing_dropout, true, grazingDropProbability(c, incidence), draws.grazing) ||
      dropped(c.dark_dropout, pixel.albedo_luminance < c.dark_luminance_max,
              c.dark_dropout_probability, draws.dark) ||
      dropped(c.reflective_dropout, pixel.reflectivity > c.reflectivity_min,
              c.reflective_dropout_probability, draws.reflective)) {
    return 0.0f;
  }
  if (c.axial_noise) {
    z += axialSigma(c, z, incidence) * Rng::boxMuller(draws.normal_u1, draws.normal_u2);
  }
  return static_cast<float>(std::max(z, 0.0));
}

float quantizeDepth(float z_m, double depth_scale) {
  if (!(z_m > 0.0f)) return 0.0f;
  const double units = std::min(std::round(z_m * depth_scale), 65535.0);
  return static_cast<float>(units / depth_scale);
}

}  // namespace strata::sim
