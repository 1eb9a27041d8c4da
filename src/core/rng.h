// Counter-based random numbers. A stream is a pure function of the keys it is
// created from (e.g. seed, pixel index, sample index), never of which thread
// or in which order it is used, so renders are bit-identical for any thread
// count and tile order.
//
// The mixing function is SplitMix64's finaliser (Steele, Lea, Flood 2014),
// which passes BigCrush when used as a counter-based generator.
#pragma once

#include <cstdint>

namespace pt {

// SplitMix64 finaliser: a bijective 64-bit mix with good avalanche.
constexpr uint64_t mix64(uint64_t z) {
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  return z ^ (z >> 31);
}

// Combines keys into one 64-bit value; order matters.
constexpr uint64_t hash_keys(uint64_t a, uint64_t b) {
  return mix64(a ^ mix64(b + 0x9e3779b97f4a7c15ULL));
}
constexpr uint64_t hash_keys(uint64_t a, uint64_t b, uint64_t c) { return hash_keys(hash_keys(a, b), c); }

// A small stream of uniform numbers: the state is a counter, each output is
// mix64(key + counter * golden gamma), i.e. SplitMix64 started at `key`.
class Rng {
 public:
  constexpr explicit Rng(uint64_t key) : state_(key) {}

  constexpr uint64_t next_u64() {
    state_ += 0x9e3779b97f4a7c15ULL;
    return mix64(state_);
  }

  // Uniform in [0, 1): the top 24 bits as a float (exactly representable).
  constexpr float next_float() { return static_cast<float>(next_u64() >> 40) * 0x1.0p-24f; }

 private:
  uint64_t state_;
};

}  // namespace pt
