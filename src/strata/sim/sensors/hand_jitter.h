#pragma once
// Smooth hand-held sway: per axis a sum of sinusoids with seeded amplitudes, frequencies and
// phases, x(t) = sum_k a_k sin(2 pi f_k t + phi_k), with exact derivatives.
#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <vector>

namespace strata::sim {

struct HandJitterConfig {
  /// Peak rotation per axis (bound on the sum of the components); 0 = none.
  double rotation_amplitude_deg = 0.8;
  /// Peak translation per axis; 0 = none.
  double translation_amplitude_m = 0.004;
  /// Frequencies are drawn uniformly in [min, max]: slow arm sway, not tremor.
  double min_frequency_hz = 0.2;
  double max_frequency_hz = 1.5;
  int components_per_axis = 3;

  /// Throws InputError naming the first bad field.
  void validate() const;
};

/// Thread safety: const methods may be called from several threads at once.
class HandJitter {
 public:
  HandJitter(const HandJitterConfig& config, std::uint64_t seed);
  /// n-th time derivative (n >= 0) of the rotation vector (rad) and of the translation (m).
  Eigen::Vector3d rotation(double t_s, int derivative = 0) const;
  Eigen::Vector3d translation(double t_s, int derivative = 0) const;

 private:
  struct Component {
    double amplitude, angular_frequency, phase;
  };
  using Axis = std::vector<Component>;
  static double evaluate(const Axis& axis, double t_s, int derivative);

  std::array<Axis, 6> axes_;  // rotation x, y, z, translation x, y, z
};

}  // namespace strata::sim
