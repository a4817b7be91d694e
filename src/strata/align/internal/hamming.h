#pragma once
// Hamming distance between 256-bit ORB descriptors, shared by the place index and the verifier.
#include <cstdint>
#include <cstring>

#include "strata/align/keyframe_features.h"

namespace strata::align::detail {

// Bits set in a word (SWAR: the portable x86-64 baseline has no popcnt instruction, and the
// compiler's library call for __builtin_popcountll is several times slower than this).
inline int popcount64(std::uint64_t x) {
  x = x - ((x >> 1) & 0x5555555555555555ULL);
  x = (x & 0x3333333333333333ULL) + ((x >> 2) & 0x3333333333333333ULL);
  x = (x + (x >> 4)) & 0x0F0F0F0F0F0F0F0FULL;
  return static_cast<int>((x * 0x0101010101010101ULL) >> 56);
}

/// Differing bits of two 32-byte descriptors at any address (hnswlib stores them unaligned, so
/// the words are copied out rather than read in place).
inline int hammingDistance(const void* a, const void* b) {
  std::uint64_t wa[4], wb[4];
  std::memcpy(wa, a, sizeof(wa));
  std::memcpy(wb, b, sizeof(wb));
  return popcount64(wa[0] ^ wb[0]) + popcount64(wa[1] ^ wb[1]) + popcount64(wa[2] ^ wb[2]) +
         popcount64(wa[3] ^ wb[3]);
}

inline int hammingDistance(const Descriptor& a, const Descriptor& b) {
  return hammingDistance(a.data(), b.data());
}

static_assert(sizeof(Descriptor) == 4 * sizeof(std::uint64_t), "ORB descriptors are 256 bits");

}  // namespace strata::align::detail
