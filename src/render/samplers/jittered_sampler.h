// Jittered (stratified) sampling of every dimension, for any sample count.
//
// Sample i of n (i = pass * n + s, s < n) of a pixel: each 2D dimension pair
// (pixel area, lens, light position, BSDF direction, ...) splits [0,1)^2 into
// an a x b grid with a * b = n, a the largest divisor of n not above sqrt(n)
// (a square grid when n is a square, 1 x n when n is prime), and puts sample s
// in cell perm(s) of it with uniform jitter inside the cell; a 1D dimension
// splits [0,1) into n strata the same way. perm is a pseudo-random permutation
// of [0, n) keyed on (seed, pixel, dimension, pass), so the strata of different
// dimensions (and pixels) are decorrelated. Each pass of n samples is
// stratified on its own.
#pragma once

#include <cstdint>

#include "core/math.h"

namespace pt {

class JitteredSampler {
 public:
  JitteredSampler(int spp, uint64_t seed);

  void start_pixel_sample(int x, int y, int index);
  float get_1d();
  Vec2f get_2d();
  Vec2f get_pixel_2d();

  // The a x b grid used for n samples (a <= b, a * b = n).
  static void grid_for(int n, int& a, int& b);

 private:
  uint64_t dimension_key(uint32_t dimension) const;

  int spp_, grid_a_, grid_b_;
  uint64_t seed_;
  uint64_t pixel_ = 0;
  uint32_t stratum_ = 0, pass_ = 0;
  uint32_t dimension_ = 1;  // dimension 0 is the pixel area
};

}  // namespace pt
