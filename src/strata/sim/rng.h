#pragma once
// Deterministic random numbers: the same seed gives the same bits on every machine and standard
// library (std:: distributions are implementation-defined, so they are not used).
// - SplitMix64 (Steele, Lea, Flood 2014) seeds and derives sub-streams.
// - xoshiro256** (Blackman & Vigna 2018, "Scrambled linear pseudorandom number generators")
//   draws the numbers.
// Sub-streams: Rng::stream(seed, a, b) hashes (seed, a, b) into an independent generator, so each
// frame / pixel row draws from its own stream and multi-threaded rendering stays deterministic.
// NOTE: normal() uses std::log/std::cos/std::sqrt; glibc's are correctly rounded in practice, other
// libms may differ in the last bit.
#include <array>
#include <cmath>
#include <cstdint>

namespace strata::sim {

/// One SplitMix64 step: advances `state` and returns a well-mixed 64-bit value.
inline std::uint64_t splitMix64(std::uint64_t& state) {
  std::uint64_t z = (state += 0x9E3779B97F4A7C15ULL);
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
  return z ^ (z >> 31);
}

/// Stateless hash of a value (one SplitMix64 finalisation).
inline std::uint64_t hash64(std::uint64_t value) { return splitMix64(value); }

/// Hash of a sequence of values: h = mix(h ^ value) per value.
inline std::uint64_t hashCombine(std::uint64_t seed, std::uint64_t a, std::uint64_t b = 0) {
  return hash64(hash64(hash64(seed) ^ a) ^ b);
}

/// xoshiro256** with uniform and normal draws. Not thread safe: one instance per thread/stream.
class Rng {
 public:
  explicit Rng(std::uint64_t seed) {
    std::uint64_t sm = seed;
    for (std::uint64_t& word : s_) word = splitMix64(sm);
  }
  /// Independent generator for sub-stream (a, b) of `seed`, e.g. (frame, row).
  static Rng stream(std::uint64_t seed, std::uint64_t a, std::uint64_t b = 0) {
    return Rng(hashCombine(seed, a, b));
  }

  std::uint64_t next() {
    const std::uint64_t result = rotl(s_[1] * 5, 7) * 9;
    const std::uint64_t t = s_[1] << 17;
    s_[2] ^= s_[0];
    s_[3] ^= s_[1];
    s_[1] ^= s_[2];
    s_[0] ^= s_[3];
    s_[2] ^= t;
    s_[3] = rotl(s_[3], 45);
    return result;
  }
  /// Uniform in [0, 1): the top 53 bits scaled by 2^-53.
  double uniform() { return static_cast<double>(next() >> 11) * 0x1.0p-53; }
  double uniform(double lo, double hi) { return lo + (hi - lo) * uniform(); }
  /// In [lo, hi], both inclusive; lo <= hi. Multiply-shift on the top 32 bits (bias < 2^-32 for
  /// the small ranges used here).
  int uniformInt(int lo, int hi) {
    const std::uint64_t span = static_cast<std::uint64_t>(hi - lo) + 1;
    return lo + static_cast<int>(((next() >> 32) * span) >> 32);
  }
  /// Standard normal by Box-Muller (boxMuller). One draw per call (the sine partner is dropped)
  /// so the number of draws per sample is fixed.
  double normal() {
    const double u1 = uniform();
    return boxMuller(u1, uniform());
  }
  /// Box-Muller on two uniforms in [0, 1): sqrt(-2 ln(1 - u1)) cos(2 pi u2), standard normal.
  static double boxMuller(double u1, double u2) {
    return std::sqrt(-2.0 * std::log(1.0 - u1)) * std::cos(2.0 * kPi * u2);
  }

 private:
  static constexpr double kPi = 3.14159265358979323846;
  static std::uint64_t rotl(std::uint64_t x, int k) { return (x << k) | (x >> (64 - k)); }
  std::array<std::uint64_t, 4> s_{};
};

}  // namespace strata::sim
