#pragma once
// Counter-based pseudo-random numbers: a value is a pure function of (seed, counters), so
// procedural textures and sensor noise are identical for any thread count or evaluation order.
// SplitMix64 finalizer (Steele, Lea, Flood: "Fast splittable pseudorandom number generators").
#include <cmath>
#include <cstdint>

namespace aperture::sim {

inline std::uint64_t MixBits(std::uint64_t x) {
  x += 0x9E3779B97F4A7C15ull;
  x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ull;
  x = (x ^ (x >> 27)) * 0x94D049BB133111EBull;
  return x ^ (x >> 31);
}

inline std::uint64_t HashCounters(std::uint64_t seed, std::uint64_t a, std::uint64_t b = 0,
                                  std::uint64_t c = 0) {
  return MixBits(MixBits(MixBits(MixBits(seed) ^ a) ^ b) ^ c);
}

// Uniform in [0, 1) from the top 53 bits of a hash.
inline double UniformFromHash(std::uint64_t h) {
  return static_cast<double>(h >> 11) * (1.0 / 9007199254740992.0);
}

// Standard normal sample from one hash (Box-Muller on two derived uniforms).
inline double NormalFromHash(std::uint64_t h) {
  const double u1 = 1.0 - UniformFromHash(h);  // (0, 1]
  const double u2 = UniformFromHash(MixBits(h));
  return std::sqrt(-2.0 * std::log(u1)) * std::cos(6.283185307179586 * u2);
}

}  // namespace aperture::sim
