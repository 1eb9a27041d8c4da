#include "render/samplers/sobol_sampler.h"

#include <algorithm>

#include "core/rng.h"
#include "render/samplers/low_discrepancy.h"

namespace pt {

namespace {

constexpr float kOneMinusEpsilon = 0x1.fffffep-1f;

// Shuffles the sample index with a nested uniform scramble of its bits: each
// bit is flipped by a hash of the more significant ones, so the indices
// [0, 2^m) (all bits from m up zero) go onto an aligned block of 2^m indices.
uint32_t shuffle_index(uint32_t index, uint32_t key) { return owen_scramble(index, key); }

}  // namespace

Vec2f SobolSampler::pair(uint32_t dimension) const {
  const uint64_t h = hash_keys(pixel_key_, dimension);
  const uint32_t j = shuffle_index(index_, static_cast<uint32_t>(h));
  const uint32_t kx = static_cast<uint32_t>(h >> 32);
  const uint32_t ky = static_cast<uint32_t>(mix64(h));
  // owen_scramble(sobol_dimension0(j)) = reverse(LK(j)): the two reversals cancel.
  const float u = fraction_to_float(reverse_bits32(laine_karras_permutation(j, kx)));
  const float v = fraction_to_float(owen_scramble(sobol_dimension1(j), ky));
  return {std::min(u, kOneMinusEpsilon), std::min(v, kOneMinusEpsilon)};
}

float SobolSampler::get_1d() {
  const uint64_t h = hash_keys(pixel_key_, dimension_++);
  const uint32_t j = shuffle_index(index_, static_cast<uint32_t>(h));
  const float u = fraction_to_float(reverse_bits32(laine_karras_permutation(j, static_cast<uint32_t>(h >> 32))));
  return std::min(u, kOneMinusEpsilon);
}

}  // namespace pt
