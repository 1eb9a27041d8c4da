#include "render/samplers/jittered_sampler.h"

#include <algorithm>

#include "core/rng.h"
#include "render/samplers/low_discrepancy.h"

namespace pt {

namespace {
constexpr float kOneMinusEpsilon = 0x1.fffffep-1f;
}

void JitteredSampler::grid_for(int n, int& a, int& b) {
  n = std::max(1, n);
  a = 1;
  for (int d = 1; d * d <= n; ++d)
    if (n % d == 0) a = d;
  b = n / a;
}

JitteredSampler::JitteredSampler(int spp, uint64_t seed) : spp_(std::max(1, spp)), seed_(seed) {
  grid_for(spp_, grid_a_, grid_b_);
}

void JitteredSampler::start_pixel_sample(int x, int y, int index) {
  pixel_ = (static_cast<uint64_t>(static_cast<uint32_t>(y)) << 32) | static_cast<uint32_t>(x);
  const uint32_t i = static_cast<uint32_t>(std::max(0, index));
  pass_ = i / static_cast<uint32_t>(spp_);
  stratum_ = i % static_cast<uint32_t>(spp_);
  dimension_ = 1;
}

uint64_t JitteredSampler::dimension_key(uint32_t dimension) const {
  return hash_keys(hash_keys(seed_, pixel_), dimension, pass_);
}

float JitteredSampler::get_1d() {
  const uint64_t key = dimension_key(dimension_++);
  const uint32_t cell = permutation_element(stratum_, static_cast<uint32_t>(spp_), key);
  Rng rng(hash_keys(key, stratum_));
  const float u = (static_cast<float>(cell) + rng.next_float()) / static_cast<float>(spp_);
  return std::min(u, kOneMinusEpsilon);
}

Vec2f JitteredSampler::get_2d() {
  const uint64_t key = dimension_key(dimension_++);
  const uint32_t cell = permutation_element(stratum_, static_cast<uint32_t>(spp_), key);
  Rng rng(hash_keys(key, stratum_));
  const float jx = rng.next_float(), jy = rng.next_float();
  // Cells are numbered row by row: a columns of width 1/a, b rows of height 1/b.
  const uint32_t cx = cell % static_cast<uint32_t>(grid_a_), cy = cell / static_cast<uint32_t>(grid_a_);
  const float u = (static_cast<float>(cx) + jx) / static_cast<float>(grid_a_);
  const float v = (static_cast<float>(cy) + jy) / static_cast<float>(grid_b_);
  return {std::min(u, kOneMinusEpsilon), std::min(v, kOneMinusEpsilon)};
}

Vec2f JitteredSampler::get_pixel_2d() {
  const uint32_t saved = dimension_;
  dimension_ = 0;
  const Vec2f p = get_2d();
  dimension_ = saved;
  return p;
}

}  // namespace pt
