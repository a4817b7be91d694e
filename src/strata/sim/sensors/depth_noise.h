#pragma once
// Structured-light depth noise model (Kinect v1 class), every effect switchable.
// Sources:
// - Axial noise: Nguyen, Izadi, Lovell, "Modeling Kinect Sensor Noise for Improved 3D
//   Reconstruction and Tracking", 3DIMPVT 2012: sigma_z(z, theta) = 0.0012 + 0.0019 (z - 0.4)^2
//   + 0.0001 / sqrt(z) * theta^2 / (pi/2 - theta)^2 metres (z in m, theta = incidence angle).
// - Grazing, dark, reflective dropout and edge flying pixels: the qualitative behaviour reported by
//   Khoshelham & Oude Elberink, "Accuracy and Resolution of Kinect Depth Data for Indoor Mapping
//   Applications", Sensors 2012, and Mallick, Das, Majumdar, "Characterizations of Noise in Kinect
//   Depth Images: A Review", IEEE Sensors J. 2014. Their thresholds and probabilities here are
//   illustrative defaults, not fitted values.
// - Quantisation: the TUM RGB-D 16-bit PNG format, depth = round(z * scale) / scale, scale 5000.
#include <cstdint>

#include "strata/sim/rng.h"

namespace strata::sim {

struct DepthNoiseConfig {
  /// Master switch: false leaves only range limits and quantisation (if `quantize`).
  bool enabled = true;

  /// Gaussian axial noise sigma(z, theta), Nguyen et al. 2012 (see the header).
  bool axial_noise = true;
  double axial_a_m = 0.0012;      // constant term
  double axial_b_per_m = 0.0019;  // quadratic coefficient, m^-1
  double axial_z0_m = 0.4;        // depth of the minimum
  double axial_angle_m = 0.0001;  // angle term coefficient, m^1.5; 0 = depth-only model
  /// Missing depth at grazing incidence: drop probability ramps smoothly from 0 at start to 1 at
  /// full. Larger angles lose more of the projected pattern.
  bool grazing_dropout = true;
  double grazing_start_deg = 70.0;
  double grazing_full_deg = 80.0;
  /// Dark (absorbing) materials: albedo luminance below the threshold drops with a probability.
  bool dark_dropout = true;
  double dark_luminance_max = 0.08;  // Rec. 709 luminance of the albedo, [0, 1]
  double dark_dropout_probability = 0.5;
  /// Reflective (specular) materials: reflectivity above the threshold drops with a probability.
  bool reflective_dropout = true;
  double reflectivity_min = 0.7;
  double reflective_dropout_probability = 0.9;
  /// Flying pixels at depth discontinuities: a pixel whose 4-neighbour lies more than the jump
  /// away takes, with the probability, a depth uniformly between the two surfaces.
  bool flying_pixels = true;
  double flying_min_jump_m = 0.1;
  double flying_pixel_probability = 0.3;
  /// Round to the 16-bit depth format (applies even when `enabled` is false).
  bool quantize = true;

  /// Throws InputError naming the first bad field (negative sigma, probability outside [0, 1]...).
  void validate() const;
};

/// What the model needs to know about one pixel's noise-free measurement.
struct DepthPixel {
  float z_true_m = 0.0f;       // > 0
  float cos_incidence = 1.0f;  // |n . d| between surface normal and ray, 1 = head-on
  float albedo_luminance = 1.0f;
  float reflectivity = 0.0f;
  float z_across_edge_m = 0.0f;  // neighbour depth across the largest discontinuity; 0 = none
};

/// One pixel's uniform random numbers in [0, 1), drawn in a fixed order whatever effects are on,
/// so switching one effect off never shifts the others' draws. The axial noise's normal deviate
/// is made from (normal_u1, normal_u2) by Box-Muller only where it is used.
struct DepthPixelDraws {
  double flying = 0.0, flying_mix = 0.0, grazing = 0.0, dark = 0.0, reflective = 0.0;
  double normal_u1 = 0.0, normal_u2 = 0.0;
  static DepthPixelDraws draw(Rng& rng);
};

/// sigma_z(z, theta) in metres; theta is clamped to 85 degrees where the angle term diverges.
double axialSigma(const DepthNoiseConfig& config, double z_m, double incidence_rad);
/// Probability that grazing incidence loses the pixel: smoothstep between start and full.
double grazingDropProbability(const DepthNoiseConfig& config, double incidence_rad);
/// Depth the sensor reports for the pixel before range limits and quantisation; 0 = dropped.
float applyDepthNoise(const DepthNoiseConfig& config, const DepthPixel& pixel,
                      const DepthPixelDraws& draws);
/// round(z * scale) / scale, saturated at 65535 / scale (the 16-bit format); 0 stays 0.
float quantizeDepth(float z_m, double depth_scale);

}  // namespace strata::sim
