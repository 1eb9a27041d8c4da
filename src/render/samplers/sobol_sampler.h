// Owen-scrambled Sobol' sampling, padded (pbrt-v4's PaddedSobolSampler
// approach, Burley 2020's hash-based scrambling).
//
// Every dimension pair d of sample i of pixel p takes point j of the 2D
// Sobol' (0,2)-sequence (dimensions 0 and 1), where j is i shuffled by a
// nested uniform scramble of its bits keyed on (seed, p, d), and Owen-scrambles
// each coordinate with keys of its own. Shuffling an index by an Owen scramble
// maps [0, 2^m) onto an aligned block of 2^m consecutive indices, so the first
// 2^m samples of every dimension pair of every pixel form a (0,m,2)-net: each
// elementary interval of area 2^-m holds exactly one point. A 1D dimension is
// the first coordinate alone (stratified into 2^m equal intervals). Different
// keys per dimension pair decorrelate the pairs; different keys per pixel
// decorrelate the pixels. Counts that are not powers of two are still valid
// (a prefix of a scrambled net), only less well stratified.
#pragma once

#include <cstdint>

#include "core/math.h"
#include "core/rng.h"
#include "render/samplers/low_discrepancy.h"

namespace pt {

class SobolSampler {
 public:
  explicit SobolSampler(uint64_t seed) : seed_(seed) {}

  void start_pixel_sample(int x, int y, int index) {
    const uint64_t pixel = (static_cast<uint64_t>(static_cast<uint32_t>(y)) << 32) | static_cast<uint32_t>(x);
    pixel_key_ = hash_keys(seed_, pixel);
    reversed_index_ = reverse_bits32(static_cast<uint32_t>(index < 0 ? 0 : index));
    dimension_ = 1;
  }
  float get_1d();
  Vec2f get_2d() { return pair(dimension_++); }
  Vec2f get_pixel_2d() { return pair(0); }

 private:
  Vec2f pair(uint32_t dimension) const;

  uint64_t seed_;
  uint64_t pixel_key_ = 0;  // hash(seed, pixel)
  uint32_t reversed_index_ = 0;  // the sample index, bits reversed
  uint32_t dimension_ = 1;  // dimension pair 0 is the pixel area
};

}  // namespace pt
