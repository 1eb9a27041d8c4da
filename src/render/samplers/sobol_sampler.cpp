#include "render/samplers/sobol_sampler.h"

#include <algorithm>

#include "core/rng.h"
#include "render/samplers/low_discrepancy.h"

namespace pt {

namespace {

constexpr float kOneMinusEpsilon = 0x1.fffffep-1f;

// Sobol' dimension 1 with its output bits reversed, one byte of the index at a
// time: reverse_bits32(sobol_dimension1(j)), so that the Owen scramble of the
// coordinate (reverse, Laine-Karras, reverse) needs one reversal, not two.
constexpr SobolByteTables reversed_dimension1_tables() {
  SobolByteTables t = kSobolDimension1Tables;
  for (auto& row : t)
    for (uint32_t& v : row) v = reverse_bits32(v);
  return t;
}
constexpr SobolByteTables kReversedDimension1 = reversed_dimension1_tables();

constexpr uint32_t reversed_dimension1(uint32_t j) {
  return kReversedDimension1[0][j & 0xffu] ^ kReversedDimension1[1][(j >> 8) & 0xffu] ^
         kReversedDimension1[2][(j >> 16) & 0xffu] ^ kReversedDimension1[3][j >> 24];
}

// The keys of dimension pair `dimension`: one SplitMix64 finalisation of the
// pixel's key and the dimension (the pixel key is itself a full hash).
uint64_t dimension_key(uint64_t pixel_key, uint32_t dimension) {
  return mix64(pixel_key ^ (static_cast<uint64_t>(dimension) * 0xd1b54a32d192ed03ULL));
}

// The sample index shuffled by a nested uniform scramble of its bits (each
// bit flipped by a hash of the more significant ones), so the indices
// [0, 2^m) go onto an aligned block of 2^m indices: owen_scramble(index, key),
// given the index's bit reversal (computed once per sample).
uint32_t shuffled_index(uint32_t reversed_index, uint32_t key) {
  return reverse_bits32(laine_karras_permutation(reversed_index, key));
}

}  // namespace

Vec2f SobolSampler::pair(uint32_t dimension) const {
  const uint64_t h = dimension_key(pixel_key_, dimension);
  const uint32_t j = shuffled_index(reversed_index_, static_cast<uint32_t>(h));
  const uint32_t kx = static_cast<uint32_t>(h >> 32);
  const uint32_t ky = static_cast<uint32_t>((h * 0x9e3779b97f4a7c15ULL) >> 32);  // depends on all of h's bits
  // owen_scramble(sobol_dimension0(j)) = reverse(LK(j)): the two reversals cancel;
  // owen_scramble(sobol_dimension1(j)) = reverse(LK(reverse(sobol1(j)))).
  const float u = fraction_to_float(reverse_bits32(laine_karras_permutation(j, kx)));
  const float v = fraction_to_float(reverse_bits32(laine_karras_permutation(reversed_dimension1(j), ky)));
  return {std::min(u, kOneMinusEpsilon), std::min(v, kOneMinusEpsilon)};
}

float SobolSampler::get_1d() {
  const uint64_t h = dimension_key(pixel_key_, dimension_++);
  const uint32_t j = shuffled_index(reversed_index_, static_cast<uint32_t>(h));
  const float u = fraction_to_float(reverse_bits32(laine_karras_permutation(j, static_cast<uint32_t>(h >> 32))));
  return std::min(u, kOneMinusEpsilon);
}

}  // namespace pt
