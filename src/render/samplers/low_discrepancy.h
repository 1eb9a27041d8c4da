// Building blocks of the stratified samplers: a (0,2)-sequence in base 2
// (Sobol' dimensions 0 and 1), hash-based Owen scrambling (Burley 2020,
// "Practical Hash-based Owen Scrambling", after Laine and Karras 2011) and a
// hash-keyed permutation of [0, n) for any n (cycle walking).
//
// Every function is pure: the same arguments give the same result.
#pragma once

#include <array>
#include <cstdint>

namespace pt {

constexpr uint32_t reverse_bits32(uint32_t v) {
  v = ((v >> 1) & 0x55555555u) | ((v & 0x55555555u) << 1);
  v = ((v >> 2) & 0x33333333u) | ((v & 0x33333333u) << 2);
  v = ((v >> 4) & 0x0f0f0f0fu) | ((v & 0x0f0f0f0fu) << 4);
  v = ((v >> 8) & 0x00ff00ffu) | ((v & 0x00ff00ffu) << 8);
  return (v >> 16) | (v << 16);
}

// Generator matrix columns of Sobol' dimension 1 (primitive polynomial x + 1,
// m_1 = 1): direction number k is v_k = v_{k-1} xor (v_{k-1} >> 1), v_0 = 2^31.
// Dimension 0 needs no table: its columns are 2^(31-k), i.e. bit reversal.
constexpr std::array<uint32_t, 32> sobol_dimension1_matrix() {
  std::array<uint32_t, 32> v{};
  v[0] = 0x80000000u;
  for (int k = 1; k < 32; ++k) v[k] = v[k - 1] ^ (v[k - 1] >> 1);
  return v;
}

// The product of the matrix with an index, one byte of the index at a time:
// table[b][v] is the xor of the columns 8b + i for the bits i set in v. The
// samplers' indices are scrambled (all 32 bits in use), so a bit loop would
// take 32 steps; four lookups take constant time.
using SobolByteTables = std::array<std::array<uint32_t, 256>, 4>;
constexpr SobolByteTables sobol_dimension1_byte_tables() {
  const std::array<uint32_t, 32> matrix = sobol_dimension1_matrix();
  SobolByteTables t{};
  for (std::size_t b = 0; b < 4; ++b)
    for (std::size_t v = 0; v < 256; ++v)
      for (std::size_t i = 0; i < 8; ++i)
        if (v & (std::size_t{1} << i)) t[b][v] ^= matrix[8 * b + i];
  return t;
}
inline constexpr SobolByteTables kSobolDimension1Tables = sobol_dimension1_byte_tables();

// Sobol' point `index`, dimension 0 (van der Corput) and 1, as 32-bit fractions.
constexpr uint32_t sobol_dimension0(uint32_t index) { return reverse_bits32(index); }
constexpr uint32_t sobol_dimension1(uint32_t index) {
  return kSobolDimension1Tables[0][index & 0xffu] ^ kSobolDimension1Tables[1][(index >> 8) & 0xffu] ^
         kSobolDimension1Tables[2][(index >> 16) & 0xffu] ^ kSobolDimension1Tables[3][index >> 24];
}

// Owen scrambling of a 32-bit fraction: every bit is flipped by a hash of the
// more significant bits and the seed (nested uniform scrambling). Applied to
// the points of a (0,m,2)-net it gives another (0,m,2)-net.
// The Laine-Karras permutation: each output bit depends only on the same and
// lower input bits (sums, and products by even constants, carry upwards only).
constexpr uint32_t laine_karras_permutation(uint32_t x, uint32_t seed) {
  x += seed;
  x ^= x * 0x6c50b47cu;
  x ^= x * 0xb82f1e52u;
  x ^= x * 0xc7afe638u;
  x ^= x * 0x8d22f6e6u;
  return x;
}
// Applied in bit-reversed order, each bit depends only on the more significant ones.
constexpr uint32_t owen_scramble(uint32_t x, uint32_t seed) {
  return reverse_bits32(laine_karras_permutation(reverse_bits32(x), seed));
}

// Element i of a pseudo-random permutation of [0, n) keyed on `key` (n >= 1,
// i < n): a bijection on the smallest power of two >= n, repeated until the
// value falls inside [0, n) (cycle walking, which keeps it a bijection).
constexpr uint32_t permutation_element(uint32_t i, uint32_t n, uint64_t key) {
  if (n <= 1) return 0;
  uint32_t mask = n - 1;
  mask |= mask >> 1;
  mask |= mask >> 2;
  mask |= mask >> 4;
  mask |= mask >> 8;
  mask |= mask >> 16;
  const uint32_t k0 = static_cast<uint32_t>(key), k1 = static_cast<uint32_t>(key >> 32);
  do {
    // Each step is a bijection on [0, mask]: xor with a constant, a product
    // by an odd number, an xor with its own right shift.
    i ^= k0 & mask;
    i = (i * 0x9e3779b1u) & mask;
    i ^= (i >> 5) & mask;
    i = (i * (k1 | 1u)) & mask;
    i ^= i >> 7;
    i = (i + (k0 >> 16)) & mask;
    i = (i * 0x85ebca6bu) & mask;
    i ^= i >> 3;
  } while (i >= n);
  return i;
}

// A 32-bit fraction as a float in [0, 1) (rounded down to 24 bits).
constexpr float fraction_to_float(uint32_t x) { return static_cast<float>(x >> 8) * 0x1.0p-24f; }

}  // namespace pt
