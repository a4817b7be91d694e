#include "strata/sim/sensors/hand_jitter.h"

#include <cmath>

#include "strata/core/error.h"
#include "strata/sim/rng.h"
#include "strata/core/math_constants.h"

namespace strata::sim {
namespace {

}  // namespace

void HandJitterConfig::validate() const {
  if (!(rotation_amplitude_deg >= 0.0) || !(translation_amplitude_m >= 0.0)) {
    throw InputError(
        "HandJitterConfig: rotation_amplitude_deg and translation_amplitude_m must "
        "be >= 0");
  }
  if (!(min_frequency_hz > 0.0 && min_frequency_hz <= max_frequency_hz) ||
      !std::isfinite(max_frequency_hz)) {
    throw InputError("HandJitterConfig: need 0 < min_frequency_hz <= max_frequency_hz, finite");
  }
  if (components_per_axis < 1)
    throw InputError("HandJitterConfig: components_per_axis must be >= 1");
}

HandJitter::HandJitter(const HandJitterConfig& config, std::uint64_t seed) {
  config.validate();
  Rng rng(seed);
  for (int a = 0; a < 6; ++a) {
    const double peak =
        a < 3 ? config.rotation_amplitude_deg * kPi / 180.0 : config.translation_amplitude_m;
    std::vector<double> weights(config.components_per_axis);
    double weight_sum = 0.0;
    for (double& w : weights) weight_sum += (w = rng.uniform(0.5, 1.0));
    for (double w : weights) {
      const double frequency = rng.uniform(config.min_frequency_hz, config.max_frequency_hz);
      // Amplitudes sum to the peak, so |x(t)| <= peak.
      axes_[a].push_back(
          {peak * w / weight_sum, 2.0 * kPi * frequency, rng.uniform(0.0, 2.0 * kPi)});
    }
  }
}

double HandJitter::evaluate(const Axis& axis, double t_s, int derivative) {
  // d^n/dt^n a sin(w t + phi) = a w^n sin(w t + phi + n pi / 2).
  double value = 0.0;
  for (const Component& c : axis) {
    value += c.amplitude * std::pow(c.angular_frequency, derivative) *
             std::sin(c.angular_frequency * t_s + c.phase + derivative * 0.5 * kPi);
  }
  return value;
}

Eigen::Vector3d HandJitter::rotation(double t_s, int derivative) const {
  return {evaluate(axes_[0], t_s, derivative), evaluate(axes_[1], t_s, derivative),
          evaluate(axes_[2], t_s, derivative)};
}

Eigen::Vector3d HandJitter::translation(double t_s, int derivative) const {
  return {evaluate(axes_[3], t_s, derivative), evaluate(axes_[4], t_s, derivative),
          evaluate(axes_[5], t_s, derivative)};
}

}  // namespace strata::sim
